// Writes scattered 32-bit words into a buffer: `words[patch.x] = patch.y` for every patch.
// The renderer hides faces of an uploaded mesh by overwriting their three indices with a
// degenerate triangle and shows them again by writing the originals back (render/delta.rs), so
// a change uploads only its patches. Patches never name the same word twice in one dispatch.

@group(0) @binding(0) var<storage, read_write> words: array<u32>;
@group(0) @binding(1) var<storage, read> patches: array<vec2<u32>>;

// Invocations per row of the dispatch grid: 65535 workgroups of 64 (the x limit).
const ROW: u32 = 4194240u;

@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let i = id.y * ROW + id.x;
    if (i >= arrayLength(&patches)) {
        return;
    }
    let p = patches[i];
    words[p.x] = p.y;
}
