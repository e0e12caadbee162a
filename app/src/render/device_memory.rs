//! How the renderer's device asks for GPU memory: in small blocks.
//!
//! wgpu sub-allocates buffers and textures out of device-memory blocks; its default hints
//! (`MemoryHints::Performance`) make the first block 128 MiB (host-visible: 64 MiB). On a software
//! adapter (lavapipe, the CI's and many headless machines') a block is host memory, and every
//! page a buffer ever used stays resident while the block lives: the window's buffers come and
//! go with every live re-cut, Preview and view toggle and land at new offsets. `MemoryUsage`
//! starts blocks at 8 MiB (host-visible: 4 MiB) but lets them double up to 64 MiB (32 MiB) as
//! more are needed; the memory test then found two 32 MiB host-visible blocks filling from 10 MB
//! to 32 MB resident each as its session went on, with the memory in use flat. [`MEMORY_HINTS`]
//! keeps host-visible blocks at [`BLOCK_SIZE`] (the smallest the allocator accepts) and
//! device-local ones at one to two times it, so a block's size bounds what it can hold resident,
//! anything bigger (a model's vertices, a render target) gets memory of its own that is freed
//! with it, and empty blocks are released: the resident size follows the buffers alive (the
//! test's highest level after the first cut fell from 309 MB to 269 MB). On a discrete GPU this
//! costs a few more allocations per load.

/// The size of a sub-allocated device-memory block (host-visible: every block; device-local: the
/// first, later ones up to twice it).
pub const BLOCK_SIZE: u64 = 4 << 20;

/// The hints every device of the renderer is opened with (window and headless).
pub const MEMORY_HINTS: wgpu::MemoryHints = wgpu::MemoryHints::Manual {
    // wgpu gives host-visible blocks half this range, clamped to at least 4 MiB: 4 MiB too.
    suballocated_device_memory_block_size: BLOCK_SIZE..2 * BLOCK_SIZE,
};

/// `setup` with its device opened with [`MEMORY_HINTS`] (everything else as it was).
pub fn with_memory_hints(setup: egui_wgpu::WgpuSetup) -> egui_wgpu::WgpuSetup {
    match setup {
        egui_wgpu::WgpuSetup::CreateNew(mut create) => {
            let base = create.device_descriptor.clone();
            create.device_descriptor = std::sync::Arc::new(move |adapter| wgpu::DeviceDescriptor {
                memory_hints: MEMORY_HINTS,
                ..base(adapter)
            });
            egui_wgpu::WgpuSetup::CreateNew(create)
        }
        existing => existing,
    }
}
