//! The one way Cutaway reads an input file: mesh files, sessions, gestures and path files all
//! come through [`read_bytes`] or [`read_text`].
//!
//! Why one place: a path given by a user may be a symbolic link to `/dev/zero`, a FIFO that never
//! ends, a socket or a 40 GB file. `std::fs::read` would block on the FIFO or read until memory
//! runs out. Here the path is resolved (links followed) and must name a regular file whose size is
//! within the caller's ceiling; the read itself is capped at the ceiling too (a file that grows
//! while it is read is cut off and refused), so no input can make Cutaway read more than the
//! ceiling, whatever the file system says.
//!
//! Ceilings: [`MESH_MAX_BYTES`] (2 GiB) for mesh files, [`JSON_MAX_BYTES`] (64 MiB) for the JSON
//! documents (sessions, gestures, path files). Every error is one line that says what the path is
//! and why it is refused; the caller adds the path.

use std::io::Read as _;
use std::path::Path;

/// Largest mesh file read (2 GiB: a binary STL of 43 million triangles).
pub const MESH_MAX_BYTES: u64 = 2 << 30;

/// Largest label-volume file read (4 GiB: a 1024³ 16-bit volume stored raw, with its header);
/// the header's sizes are checked against the data before any voxel buffer is allocated.
pub const VOLUME_MAX_BYTES: u64 = 4 << 30;

/// Largest JSON document read (sessions, gestures, path files): 64 MiB.
pub const JSON_MAX_BYTES: u64 = 64 << 20;

/// Reads the whole regular file at `path` (symbolic links followed), refusing directories,
/// special files (FIFOs, devices, sockets) and files larger than `max_bytes`. Errors do not name
/// the file (the caller adds it).
pub fn read_bytes(path: &Path, max_bytes: u64) -> anyhow::Result<Vec<u8>> {
    let metadata = std::fs::metadata(path)?;
    check_kind_and_size(&metadata, max_bytes)?;
    let file = std::fs::File::open(path)?;
    // The path may have been replaced between the two calls: check what was opened.
    let opened = file.metadata()?;
    check_kind_and_size(&opened, max_bytes)?;
    let mut bytes = Vec::with_capacity(opened.len() as usize);
    file.take(max_bytes + 1).read_to_end(&mut bytes)?;
    if bytes.len() as u64 > max_bytes {
        anyhow::bail!(
            "grew past the limit of {} while it was read; refusing it",
            describe_size(max_bytes)
        );
    }
    Ok(bytes)
}

/// [`read_bytes`] for a UTF-8 text file.
pub fn read_text(path: &Path, max_bytes: u64) -> anyhow::Result<String> {
    let bytes = read_bytes(path, max_bytes)?;
    String::from_utf8(bytes).map_err(|e| {
        anyhow::anyhow!(
            "not a UTF-8 text file (invalid byte at offset {})",
            e.utf8_error().valid_up_to()
        )
    })
}

fn check_kind_and_size(metadata: &std::fs::Metadata, max_bytes: u64) -> anyhow::Result<()> {
    let kind = metadata.file_type();
    if kind.is_dir() {
        anyhow::bail!("is a directory, not a file");
    }
    if !kind.is_file() {
        anyhow::bail!(
            "is {}, not a regular file; refusing to read it",
            special_kind(&kind)
        );
    }
    if metadata.len() > max_bytes {
        anyhow::bail!(
            "is {} bytes, more than the limit of {} for this kind of file",
            metadata.len(),
            describe_size(max_bytes)
        );
    }
    Ok(())
}

fn special_kind(kind: &std::fs::FileType) -> &'static str {
    use std::os::unix::fs::FileTypeExt as _;
    if kind.is_fifo() {
        "a FIFO (named pipe)"
    } else if kind.is_char_device() {
        "a character device"
    } else if kind.is_block_device() {
        "a block device"
    } else if kind.is_socket() {
        "a socket"
    } else {
        "a special file"
    }
}

fn describe_size(bytes: u64) -> String {
    match bytes {
        b if b >= 1 << 30 && b.is_multiple_of(1 << 30) => format!("{} GiB", b >> 30),
        b if b >= 1 << 20 && b.is_multiple_of(1 << 20) => format!("{} MiB", b >> 20),
        b => format!("{b} bytes"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn temp_dir(name: &str) -> std::path::PathBuf {
        let dir =
            std::env::temp_dir().join(format!("cutaway-bounded-{name}-{}", std::process::id()));
        std::fs::remove_dir_all(&dir).ok();
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }

    #[test]
    fn special_files_are_refused_before_reading() {
        let dir = temp_dir("special");
        let zero = dir.join("zero.stl");
        std::os::unix::fs::symlink("/dev/zero", &zero).unwrap();
        let e = format!("{:#}", read_bytes(&zero, MESH_MAX_BYTES).unwrap_err());
        assert!(e.contains("character device"), "{e}");
        let fifo = dir.join("pipe.json");
        let made = std::process::Command::new("mkfifo").arg(&fifo).status();
        if made.is_ok_and(|s| s.success()) {
            // Opening a FIFO without a writer would block: the kind is checked first.
            let e = format!("{:#}", read_text(&fifo, JSON_MAX_BYTES).unwrap_err());
            assert!(e.contains("FIFO"), "{e}");
        } else {
            eprintln!("FIFO case skipped: mkfifo is not available");
        }
        let e = format!("{:#}", read_bytes(&dir, MESH_MAX_BYTES).unwrap_err());
        assert!(e.contains("directory"), "{e}");
        std::fs::remove_dir_all(&dir).ok();
    }

    #[test]
    fn files_over_the_ceiling_are_refused_by_size() {
        let dir = temp_dir("size");
        let big = dir.join("big.obj");
        // A sparse 40 GB file: nothing is read, the size alone refuses it.
        let file = std::fs::File::create(&big).unwrap();
        file.set_len(40_000_000_000).unwrap();
        let e = format!("{:#}", read_bytes(&big, MESH_MAX_BYTES).unwrap_err());
        assert!(
            e.contains("40000000000 bytes") && e.contains("2 GiB"),
            "{e}"
        );
        std::fs::write(&big, b"12345").unwrap();
        assert!(read_bytes(&big, 4).is_err());
        assert_eq!(read_bytes(&big, 5).unwrap(), b"12345");
        std::fs::write(&big, [b'a', 0xff]).unwrap();
        let e = format!("{:#}", read_text(&big, 5).unwrap_err());
        assert!(e.contains("offset 1"), "{e}");
        std::fs::remove_dir_all(&dir).ok();
    }
}
