//! Inflating gzip data with a limit: never more than the header promised, never an allocation
//! sized by the header alone.
//!
//! The output buffer starts at the smaller of the expected size and what the compressed bytes
//! could possibly inflate to (deflate's best ratio is about 1032:1), and grows only as data
//! really arrives; the stream is cut one byte past the expected size, so too much data is seen
//! without inflating all of it.

use std::io::Read;

/// Deflate cannot compress better than this (258-byte matches coded in 2 bits, rounded up).
const MAX_RATIO: usize = 1032;

/// Inflates a gzip stream (several members are one stream, as `gzip -c a b` writes) to exactly
/// `expected` bytes. `what` names the data in messages (`"voxel data"`).
pub fn inflate_exact(compressed: &[u8], expected: usize, what: &str) -> anyhow::Result<Vec<u8>> {
    let limit = expected.saturating_add(1);
    let start = expected.min(compressed.len().saturating_mul(MAX_RATIO));
    let mut out = Vec::with_capacity(start);
    flate2::read::MultiGzDecoder::new(compressed)
        .take(limit as u64)
        .read_to_end(&mut out)
        .map_err(|e| anyhow::anyhow!("corrupt or truncated gzip {what} ({e})"))?;
    match out.len().cmp(&expected) {
        std::cmp::Ordering::Equal => Ok(out),
        std::cmp::Ordering::Less => anyhow::bail!(
            "{what} is {} bytes after gzip, but the header's sizes and type need {expected}",
            out.len()
        ),
        std::cmp::Ordering::Greater => anyhow::bail!(
            "{what} is more than the {expected} bytes the header's sizes and type need"
        ),
    }
}

/// Reads from `reader` exactly `expected` bytes; fewer is an error. Growth as for
/// [`inflate_exact`], bounded by `compressed_len` × the deflate ratio.
/// Appends to `out`, whose capacity is used first (a caller reading many files of one size, a
/// mask folder, inflates each into the same buffer instead of touching a fresh one per file).
pub fn read_exact_limited_onto(
    reader: &mut dyn Read,
    expected: usize,
    compressed_len: usize,
    what: &str,
    out: &mut Vec<u8>,
) -> anyhow::Result<()> {
    let before = out.len();
    let start = expected.min(compressed_len.saturating_mul(MAX_RATIO));
    out.reserve(start);
    reader
        .take(expected as u64)
        .read_to_end(out)
        .map_err(|e| anyhow::anyhow!("corrupt or truncated gzip {what} ({e})"))?;
    if out.len() - before < expected {
        anyhow::bail!(
            "{what} is {} bytes, but the header's sizes and type need {expected}",
            out.len() - before
        );
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::io::Write as _;

    fn gz(data: &[u8]) -> Vec<u8> {
        let mut e = flate2::write::GzEncoder::new(Vec::new(), flate2::Compression::fast());
        e.write_all(data).unwrap();
        e.finish().unwrap()
    }

    #[test]
    fn exact_size_inflates_and_mismatches_are_errors() {
        let data = vec![7u8; 1000];
        let packed = gz(&data);
        assert_eq!(inflate_exact(&packed, 1000, "voxel data").unwrap(), data);
        let short = inflate_exact(&packed, 1001, "voxel data").unwrap_err();
        assert!(short.to_string().contains("is 1000 bytes"), "{short}");
        let long = inflate_exact(&packed, 999, "voxel data").unwrap_err();
        assert!(
            long.to_string().contains("more than the 999 bytes"),
            "{long}"
        );
    }

    #[test]
    fn truncated_and_corrupt_streams_are_errors() {
        let packed = gz(&(0..5000u32)
            .map(|i| (i * 7 % 251) as u8)
            .collect::<Vec<_>>());
        let truncated = &packed[..packed.len() / 2];
        let err = inflate_exact(truncated, 5000, "voxel data").unwrap_err();
        assert!(
            err.to_string().contains("corrupt or truncated gzip"),
            "{err}"
        );
        let mut corrupt = packed.clone();
        for b in &mut corrupt[12..40] {
            *b ^= 0x5a;
        }
        assert!(inflate_exact(&corrupt, 5000, "voxel data").is_err());
        assert!(inflate_exact(b"not gzip at all", 10, "voxel data").is_err());
    }

    #[test]
    fn a_huge_claim_allocates_by_the_input_not_the_claim() {
        // A 40-byte stream claiming 16 GB: the buffer starts at most 40 × 1032 bytes and the
        // read ends with a size error.
        let packed = gz(&[1u8; 10]);
        let err = inflate_exact(&packed, 16 << 30, "voxel data").unwrap_err();
        assert!(err.to_string().contains("is 10 bytes"), "{err}");
    }
}
