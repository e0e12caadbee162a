//! How the renderer's device asks for GPU memory: in small blocks.
//!
//! wgpu sub-allocates buffers out of device-memory blocks; its default hints
//! (`MemoryHints::Performance`) make the first block 128 MiB (host-visible: 64 MiB). On a software
//! adapter (lavapipe, the CI's and many headless machines') a block is host memory, and every
//! page a buffer ever used stays resident while the block lives: the window's buffers come and
//! go with every live re-cut, Preview and view toggle, land at new offsets, and the memory test
//! saw the resident size climb by ~90 MB over its session with the memory in use flat. With
//! `MemoryHints::MemoryUsage` blocks start at 8 MiB (host: 4 MiB), a model-sized buffer gets
//! memory of its own that is freed with it, and empty blocks are released, so the resident size
//! follows the buffers alive. On a discrete GPU this costs a few more allocations per load.

/// The hints every device of the renderer is opened with (window and headless).
pub const MEMORY_HINTS: wgpu::MemoryHints = wgpu::MemoryHints::MemoryUsage;

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
