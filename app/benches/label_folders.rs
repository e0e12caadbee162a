//! TotalSegmentator-size inputs through `cutaway surfaces`: a folder of one full-size `.nii.gz`
//! mask per structure, and the same structures as one label map.
//!
//! ```text
//! CUTAWAY_ANATOMY=DIR cargo bench -p cutaway --bench label_folders -- [--scale 1,2] [--masks 117] [--keep DIR]
//! ```
//! The inputs are generated, never committed: the SPL head atlas upsampled `scale` times along
//! each axis by nearest neighbour (scale 2: 512³, as a whole-body CT grid), its `--masks` largest
//! labels written as separate uint8 NIfTI-1 masks of the full grid (`masks/<value>_<name>.nii.gz`)
//! and as one uint16 map (`map.nii.gz`). For each scale it prints, from one run:
//! - the baseline: inflating every mask file on all cores (the least any reader pays), with
//!   `flate2` as built (its reader, as the volume readers use it) and with `miniz_oxide` called
//!   directly, side by side (build with `flate2`'s `zlib-rs` feature to compare that backend);
//! - `cutaway surfaces` on the folder and on the map: `surfaces_ms`, the process's wall time,
//!   CPU time and peak resident memory (from `/usr/bin/time` where present), ms per million
//!   voxels (all masks' voxels for the folder) and per million triangles written.

use std::io::Write as _;
use std::path::{Path, PathBuf};
use std::time::Instant;

use cutaway::io::volume::{LabelData, read_volume};
use rayon::prelude::*;

#[path = "support/surfaces_run.rs"]
mod surfaces_run;
use surfaces_run::{load_average, or_unknown, run_surfaces};

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let value_of = |flag: &str| {
        args.iter()
            .position(|a| a == flag)
            .and_then(|i| args.get(i + 1))
            .cloned()
    };
    let scales: Vec<usize> = value_of("--scale")
        .unwrap_or_else(|| "1,2".into())
        .split(',')
        .map(|s| s.parse().expect("--scale: integers"))
        .collect();
    let masks: usize = value_of("--masks").map_or(117, |s| s.parse().expect("--masks"));
    let Some(root) = std::env::var_os("CUTAWAY_ANATOMY") else {
        println!("label_folders bench skipped: CUTAWAY_ANATOMY is not set");
        return;
    };
    let atlas = Path::new(&root).join("volumes/spl_head_atlas/hncma-atlas.nrrd");
    let work = value_of("--keep").map_or_else(
        || std::env::temp_dir().join(format!("label_folders_{}", std::process::id())),
        PathBuf::from,
    );
    println!("load average {}", load_average());
    for scale in scales {
        let dir = work.join(format!("scale{scale}"));
        let start = Instant::now();
        let grid = generate(&atlas, scale, masks, &dir);
        println!(
            "\n== {}x{}x{} ({} masks of {:.1} M voxels each; generated in {:.1} s)",
            grid.dims[0],
            grid.dims[1],
            grid.dims[2],
            grid.masks,
            grid.voxels as f64 / 1e6,
            start.elapsed().as_secs_f64()
        );
        inflate_baseline(&dir.join("masks"));
        for (what, input, voxels) in [
            (
                "folder of masks",
                dir.join("masks"),
                grid.voxels * grid.masks as u64,
            ),
            ("one label map", dir.join("map.nii.gz"), grid.voxels),
        ] {
            surfaces(what, &input, &dir.join("out"), voxels);
        }
        if value_of("--keep").is_none() {
            std::fs::remove_dir_all(&dir).ok();
        }
    }
}

struct Generated {
    dims: [usize; 3],
    voxels: u64,
    masks: usize,
}

/// Writes `dir/masks/*.nii.gz` and `dir/map.nii.gz` (see the module doc).
fn generate(atlas: &Path, scale: usize, count: usize, dir: &Path) -> Generated {
    let volume = read_volume(atlas, None).unwrap_or_else(|e| panic!("{e:#}"));
    let LabelData::U16(src) = &volume.layers[0] else {
        panic!("the atlas is expected as a 16-bit label map");
    };
    let [sx, sy, sz] = volume.dims;
    let dims = [sx * scale, sy * scale, sz * scale];
    let voxels = dims.iter().product::<usize>();
    let mut largest = volume.structures.clone();
    largest.sort_by_key(|s| std::cmp::Reverse(s.voxels));
    largest.truncate(count);
    let keep: std::collections::HashSet<u32> = largest.iter().map(|s| s.value).collect();
    let mut map = vec![0u16; voxels];
    map.par_chunks_mut(dims[0] * dims[1])
        .enumerate()
        .for_each(|(k, slice)| {
            for j in 0..dims[1] {
                for i in 0..dims[0] {
                    let v = src[i / scale + sx * (j / scale + sy * (k / scale))];
                    slice[i + dims[0] * j] = if keep.contains(&(v as u32)) { v } else { 0 };
                }
            }
        });
    // Voxel index → world: the atlas's matrix with each axis divided by the scale, so the
    // upsampled grid covers the same anatomy.
    let m = volume.world_from_voxel;
    let s = scale as f64;
    let half = (s - 1.0) / (2.0 * s);
    let world = glam::DAffine3::from_mat3_translation(
        glam::DMat3::from_cols(
            m.matrix3.x_axis / s,
            m.matrix3.y_axis / s,
            m.matrix3.z_axis / s,
        ),
        m.transform_point3(glam::DVec3::splat(-half)),
    );
    let masks_dir = dir.join("masks");
    std::fs::create_dir_all(&masks_dir).unwrap();
    largest.par_iter().for_each(|s| {
        let name = format!("{}_{}.nii.gz", s.value, sanitize(&s.name));
        let bytes: Vec<u8> = map.iter().map(|&v| u8::from(v as u32 == s.value)).collect();
        write_nifti(&masks_dir.join(name), dims, &world, 2, &bytes);
    });
    let bytes: Vec<u8> = map.iter().flat_map(|v| v.to_le_bytes()).collect();
    write_nifti(&dir.join("map.nii.gz"), dims, &world, 512, &bytes);
    Generated {
        dims,
        voxels: voxels as u64,
        masks: largest.len(),
    }
}

fn sanitize(name: &str) -> String {
    name.chars()
        .map(|c| if c.is_ascii_alphanumeric() { c } else { '_' })
        .collect()
}

/// A gzip-compressed NIfTI-1 file: `datatype` 2 (uint8) or 512 (uint16), sform = `world`.
fn write_nifti(path: &Path, dims: [usize; 3], world: &glam::DAffine3, datatype: i16, data: &[u8]) {
    let mut h = vec![0u8; 352];
    let put_i16 =
        |h: &mut Vec<u8>, at: usize, v: i16| h[at..at + 2].copy_from_slice(&v.to_le_bytes());
    let put_f32 =
        |h: &mut Vec<u8>, at: usize, v: f32| h[at..at + 4].copy_from_slice(&v.to_le_bytes());
    h[0..4].copy_from_slice(&348i32.to_le_bytes());
    for (k, d) in [3, dims[0], dims[1], dims[2], 1, 1, 1, 1]
        .iter()
        .enumerate()
    {
        put_i16(&mut h, 40 + 2 * k, *d as i16);
    }
    put_i16(&mut h, 70, datatype);
    put_i16(&mut h, 72, if datatype == 2 { 8 } else { 16 });
    let m = world.matrix3;
    let spacing = [m.x_axis.length(), m.y_axis.length(), m.z_axis.length()];
    put_f32(&mut h, 76, 1.0);
    for (k, s) in spacing.iter().enumerate() {
        put_f32(&mut h, 80 + 4 * k, *s as f32);
    }
    put_f32(&mut h, 108, 352.0);
    put_f32(&mut h, 112, 1.0);
    put_i16(&mut h, 254, 1);
    let rows = [
        [m.x_axis.x, m.y_axis.x, m.z_axis.x, world.translation.x],
        [m.x_axis.y, m.y_axis.y, m.z_axis.y, world.translation.y],
        [m.x_axis.z, m.y_axis.z, m.z_axis.z, world.translation.z],
    ];
    for (r, row) in rows.iter().enumerate() {
        for (c, v) in row.iter().enumerate() {
            put_f32(&mut h, 280 + 16 * r + 4 * c, *v as f32);
        }
    }
    h[344..348].copy_from_slice(b"n+1\0");
    let file = std::fs::File::create(path).unwrap();
    let mut gz =
        flate2::write::GzEncoder::new(std::io::BufWriter::new(file), flate2::Compression::new(6));
    gz.write_all(&h).unwrap();
    gz.write_all(data).unwrap();
    gz.finish().unwrap().flush().unwrap();
}

/// Inflates every file of `dir` on all cores, once with `flate2` and once with `miniz_oxide`
/// directly (raw deflate after the gzip header), and prints both.
fn inflate_baseline(dir: &Path) {
    let files: Vec<Vec<u8>> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| std::fs::read(e.unwrap().path()).unwrap())
        .collect();
    let compressed: usize = files.iter().map(Vec::len).sum();
    let run = |name: &str, inflate: &(dyn Fn(&[u8]) -> usize + Sync)| {
        let start = Instant::now();
        let bytes: usize = files.par_iter().map(|f| inflate(f)).sum();
        let s = start.elapsed().as_secs_f64();
        println!(
            "inflate baseline ({name}, {} threads): {:.0} ms for {:.1} MB → {:.0} MB ({:.0} MB/s)",
            rayon::current_num_threads(),
            s * 1e3,
            compressed as f64 / 1e6,
            bytes as f64 / 1e6,
            bytes as f64 / 1e6 / s
        );
    };
    run("flate2 as built", &|f| {
        let mut out = Vec::new();
        std::io::Read::read_to_end(&mut flate2::read::MultiGzDecoder::new(f), &mut out).unwrap();
        out.len()
    });
    run("miniz_oxide", &|f| {
        // Our generator writes a plain 10-byte gzip header (no name, no extra field).
        assert_eq!(f[3], 0, "a gzip header with optional fields");
        let size = u32::from_le_bytes(f[f.len() - 4..].try_into().unwrap()) as usize;
        miniz_oxide::inflate::decompress_to_vec_with_limit(&f[10..f.len() - 8], size)
            .unwrap()
            .len()
    });
}

/// Runs `cutaway surfaces INPUT --out OUT` and prints its figures.
fn surfaces(what: &str, input: &Path, out: &Path, voxels: u64) {
    let load = load_average();
    let run = run_surfaces(input, out);
    println!(
        "surfaces, {what}: {} labels (all closed: {}), {:.2} M triangles; surfaces_ms {:.0}, process {:.0} ms ({:.2}× surfaces_ms), CPU {}, peak {}; {:.2} ms per M voxels, {:.0} ms per M triangles (load {load})",
        run.labels,
        run.all_closed,
        run.triangles as f64 / 1e6,
        run.surfaces_ms,
        run.wall_ms,
        run.wall_ms / run.surfaces_ms,
        or_unknown(run.cpu_s, "s"),
        or_unknown(run.peak_mb, "MB"),
        run.surfaces_ms / (voxels as f64 / 1e6),
        run.surfaces_ms / (run.triangles as f64 / 1e6),
    );
}
