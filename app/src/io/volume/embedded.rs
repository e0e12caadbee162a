//! Label volumes compiled into the binary (the default scene's atlas). The bytes of a NRRD file
//! and the text of its colour table go through the same header parsing, size checks, decoding
//! and naming as a volume read from disk, so the embedded atlas is exactly the file it was made
//! from; only where the bytes come from differs.

use std::path::Path;

use anyhow::Context as _;

use super::LabelVolume;

/// Reads an attached-data NRRD label map held in memory, named and coloured by the colour table
/// `table` (3D Slicer `.ctbl` text). `source` is the path the volume's structures carry (errors
/// name it).
pub fn read_embedded(source: &Path, nrrd: &[u8], table: &str) -> anyhow::Result<LabelVolume> {
    let name = || source.display().to_string();
    let raw = super::nrrd::read_attached(nrrd.to_vec()).with_context(name)?;
    let names = super::color_table::parse(table).with_context(name)?;
    super::finish(source, raw, &names).with_context(name)
}
