//! The glTF 2.0 binary container (`.glb`): a 12-byte header, a JSON chunk and a BIN chunk.
//!
//! Layout (glTF 2.0 specification, "GLB File Format Specification"): every value is a
//! little-endian `u32`. Header: magic `glTF`, version 2, total length. Each chunk: its length
//! (padded), its type (`JSON` or `BIN\0`), then its bytes. Both chunks start and end on 4-byte
//! boundaries: the JSON chunk is padded with spaces (so it stays valid JSON), the BIN chunk with
//! zeros. The JSON's one buffer has no `uri` and a `byteLength` of the unpadded BIN data.

/// `glTF` as a little-endian `u32`.
const MAGIC: u32 = 0x4654_6C67;
/// Container version this writer produces.
const VERSION: u32 = 2;
/// Chunk type of the JSON chunk (`JSON`).
const CHUNK_JSON: u32 = 0x4E4F_534A;
/// Chunk type of the binary chunk (`BIN\0`).
const CHUNK_BIN: u32 = 0x004E_4942;

/// Why a container cannot be written.
#[derive(Debug, thiserror::Error)]
pub enum GlbError {
    /// The format stores lengths as `u32`: a scene over 4 GiB does not fit.
    #[error("the glTF binary would be {bytes} bytes; the format's limit is 4 GiB")]
    TooLarge { bytes: u64 },
}

/// `json` (UTF-8) and `bin` (the buffer's bytes; may be empty, then no BIN chunk is written)
/// as one `.glb` file.
pub fn glb_bytes(json: &[u8], bin: &[u8]) -> Result<Vec<u8>, GlbError> {
    let json_padded = padded_len(json.len());
    let bin_padded = padded_len(bin.len());
    let bin_chunk = if bin.is_empty() { 0 } else { 8 + bin_padded };
    let total = 12 + 8 + json_padded as u64 + bin_chunk as u64;
    let total32 = u32::try_from(total).map_err(|_| GlbError::TooLarge { bytes: total })?;
    let mut out = Vec::with_capacity(total as usize);
    for word in [MAGIC, VERSION, total32, json_padded as u32, CHUNK_JSON] {
        out.extend_from_slice(&word.to_le_bytes());
    }
    out.extend_from_slice(json);
    out.resize(out.len() + json_padded - json.len(), b' ');
    if !bin.is_empty() {
        out.extend_from_slice(&(bin_padded as u32).to_le_bytes());
        out.extend_from_slice(&CHUNK_BIN.to_le_bytes());
        out.extend_from_slice(bin);
        out.resize(out.len() + bin_padded - bin.len(), 0);
    }
    debug_assert_eq!(out.len() as u64, total);
    Ok(out)
}

/// `len` rounded up to a multiple of 4.
pub fn padded_len(len: usize) -> usize {
    len.div_ceil(4) * 4
}

#[cfg(test)]
mod tests {
    use super::*;

    fn word(bytes: &[u8], at: usize) -> u32 {
        u32::from_le_bytes(bytes[at..at + 4].try_into().unwrap())
    }

    #[test]
    fn chunks_are_padded_to_four_bytes_and_lengths_add_up() {
        let json = br#"{"asset":{"version":"2.0"}}"#; // 27 bytes
        let bin = [1u8, 2, 3, 4, 5];
        let glb = glb_bytes(json, &bin).unwrap();
        assert_eq!(&glb[0..4], b"glTF");
        assert_eq!(word(&glb, 4), 2);
        assert_eq!(word(&glb, 8) as usize, glb.len());
        assert_eq!(glb.len() % 4, 0);
        assert_eq!(word(&glb, 12), 28);
        assert_eq!(&glb[16..20], b"JSON");
        assert_eq!(&glb[20..47], json);
        assert_eq!(glb[47], b' ', "JSON padded with a space");
        assert_eq!(word(&glb, 48), 8);
        assert_eq!(&glb[52..56], b"BIN\0");
        assert_eq!(&glb[56..61], &bin);
        assert_eq!(&glb[61..64], &[0, 0, 0], "BIN padded with zeros");
    }

    #[test]
    fn no_bin_chunk_without_data() {
        let glb = glb_bytes(b"{}  ", &[]).unwrap();
        assert_eq!(glb.len(), 12 + 8 + 4);
        assert_eq!(word(&glb, 8), 24);
    }
}
