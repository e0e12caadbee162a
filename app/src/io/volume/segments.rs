//! 3D Slicer segment metadata in NRRD key/value pairs (`.seg.nrrd`): `Segment{N}_Name`,
//! `_Color` (three floats in 0..=1), `_LabelValue` and `_Layer`.
//!
//! Older Slicer files have neither `_LabelValue` nor `_Layer`: each segment is then its own
//! layer holding the value 1 (when the file has one layer per segment), else value N+1 in layer 0.

use std::collections::BTreeMap;

use super::LabelInfo;

/// The segments named in `keys`, in segment-number order. `layers` is the file's layer count.
pub fn from_keys(keys: &[(String, String)], layers: usize) -> anyhow::Result<Vec<LabelInfo>> {
    let mut segments: BTreeMap<u32, BTreeMap<&str, &str>> = BTreeMap::new();
    for (key, value) in keys {
        let Some(rest) = key.strip_prefix("Segment") else {
            continue;
        };
        let Some((number, field)) = rest.split_once('_') else {
            continue;
        };
        let Ok(number) = number.parse::<u32>() else {
            continue;
        };
        segments
            .entry(number)
            .or_default()
            .insert(field, value.trim());
    }
    let one_layer_each = layers > 1 && layers == segments.len();
    let mut out = Vec::with_capacity(segments.len());
    for (position, (number, fields)) in segments.iter().enumerate() {
        let at = |what: &str| format!("Segment{number}_{what}");
        let value = match fields.get("LabelValue") {
            Some(v) => v
                .parse::<u32>()
                .map_err(|_| anyhow::anyhow!("{}: not a label value: '{v}'", at("LabelValue")))?,
            None if one_layer_each => 1,
            None => number
                .checked_add(1)
                .ok_or_else(|| anyhow::anyhow!("{}: segment number too large", at("Name")))?,
        };
        let layer = match fields.get("Layer") {
            Some(v) => v
                .parse::<usize>()
                .map_err(|_| anyhow::anyhow!("{}: not a layer number: '{v}'", at("Layer")))?,
            None if one_layer_each => position,
            None => 0,
        };
        if layer >= layers {
            anyhow::bail!(
                "{}: layer {layer}, but the file has {layers} layer(s)",
                at("Layer")
            );
        }
        let color = match fields.get("Color") {
            Some(text) => Some(color(text).ok_or_else(|| {
                anyhow::anyhow!(
                    "{}: expected three numbers in 0..=1, got '{text}'",
                    at("Color")
                )
            })?),
            None => None,
        };
        let name = fields
            .get("Name")
            .map(|n| n.to_string())
            .filter(|n| !n.is_empty())
            .unwrap_or_else(|| format!("label {value}"));
        out.push(LabelInfo {
            layer: Some(layer),
            value,
            name,
            color,
        });
    }
    Ok(out)
}

/// `0.992157 0.909804 0.619608` → sRGB bytes.
fn color(text: &str) -> Option<[u8; 3]> {
    let parts: Vec<f64> = text
        .split_whitespace()
        .map(|s| s.parse::<f64>().ok())
        .collect::<Option<_>>()?;
    let rgb: [f64; 3] = parts.try_into().ok()?;
    rgb.iter()
        .all(|c| (0.0..=1.0).contains(c))
        .then(|| rgb.map(|c| (c * 255.0).round() as u8))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn keys(pairs: &[(&str, &str)]) -> Vec<(String, String)> {
        pairs
            .iter()
            .map(|(k, v)| (k.to_string(), v.to_string()))
            .collect()
    }

    #[test]
    fn segments_with_layers_values_and_colours() {
        let k = keys(&[
            ("Segment0_Name", "ribs"),
            ("Segment0_Color", "0.992157 0.909804 0.619608"),
            ("Segment0_LabelValue", "1"),
            ("Segment0_Layer", "0"),
            ("Segment7_Name", "overlapping sphere"),
            ("Segment7_LabelValue", "1"),
            ("Segment7_Layer", "1"),
            ("Segmentation_MasterRepresentation", "Binary labelmap"),
        ]);
        let s = from_keys(&k, 2).unwrap();
        assert_eq!(s.len(), 2);
        assert_eq!(
            (s[0].layer, s[0].value, s[0].name.as_str()),
            (Some(0), 1, "ribs")
        );
        assert_eq!(s[0].color, Some([253, 232, 158]));
        assert_eq!((s[1].layer, s[1].value, s[1].color), (Some(1), 1, None));
        assert!(
            from_keys(&k, 1)
                .unwrap_err()
                .to_string()
                .contains("Segment7_Layer: layer 1")
        );
    }

    #[test]
    fn old_files_without_values_have_one_layer_per_segment() {
        let k = keys(&[("Segment0_Name", "a"), ("Segment1_Name", "b")]);
        let s = from_keys(&k, 2).unwrap();
        assert_eq!((s[1].layer, s[1].value), (Some(1), 1));
        let s = from_keys(&k, 1).unwrap();
        assert_eq!((s[1].layer, s[1].value), (Some(0), 2));
    }

    #[test]
    fn bad_values_are_errors() {
        let k = keys(&[("Segment0_LabelValue", "x")]);
        assert!(from_keys(&k, 1).is_err());
        let k = keys(&[("Segment0_Color", "1 2 3")]);
        assert!(
            from_keys(&k, 1)
                .unwrap_err()
                .to_string()
                .contains("Segment0_Color")
        );
    }
}
