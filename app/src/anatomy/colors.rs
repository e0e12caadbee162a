//! Colours for structures by anatomical name, so a folder of atlas files opens looking like
//! anatomy (ventricles blue, hippocampus yellow, muscle red) instead of in random hues.
//!
//! The one module that decides structure colours. The table is data,
//! `assets/anatomy_colors.txt` (values from 3D Slicer's public GenericAnatomyColors and SPL brain
//! atlas tables; provenance in `assets/README.md`), compiled into the binary and parsed once. A
//! structure's colour is, in order: the colour its file gives it, the colour of the
//! best-matching entry of this table ([`color_for_name`]), a distinct palette colour
//! ([`distinct_colors`]); all three in [`structure_color`]. The embedded phantoms' parts are
//! coloured by class ([`class_color`]). A label volume colours a label its table does not name
//! as part of reading the file (`crate::io::volume::default_color`, by the label's value).

use std::sync::OnceLock;

/// The table's text, as shipped.
const TABLE: &str = include_str!("../../../assets/anatomy_colors.txt");

/// One entry: its words (lower case) and its sRGB colour in 0..=1.
#[derive(Debug)]
struct Entry {
    words: Vec<String>,
    color: [f32; 3],
}

fn table() -> &'static [Entry] {
    static PARSED: OnceLock<Vec<Entry>> = OnceLock::new();
    PARSED.get_or_init(|| parse(TABLE).expect("assets/anatomy_colors.txt is well formed"))
}

/// Parses `name r g b` lines (`#` starts a comment line). Errors name the line.
fn parse(text: &str) -> Result<Vec<Entry>, String> {
    let mut entries = Vec::new();
    for (number, line) in text.lines().enumerate() {
        let line = line.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let fields: Vec<&str> = line.split_whitespace().collect();
        let [name, r, g, b] = fields.as_slice() else {
            return Err(format!("line {}: expected `name r g b`", number + 1));
        };
        let mut color = [0.0f32; 3];
        for (slot, text) in color.iter_mut().zip([r, g, b]) {
            let value: u8 = text
                .parse()
                .map_err(|_| format!("line {}: {text:?} is not 0..255", number + 1))?;
            *slot = f32::from(value) / 255.0;
        }
        entries.push(Entry {
            words: name.split('_').map(str::to_ascii_lowercase).collect(),
            color,
        });
    }
    Ok(entries)
}

/// The lower-case words of a name (split at anything that is not a letter or digit).
fn words_of(name: &str) -> Vec<String> {
    name.split(|c: char| !c.is_alphanumeric())
        .filter(|w| !w.is_empty())
        .map(str::to_lowercase)
        .collect()
}

/// True when `needle` occurs in `hay` in order (other words may lie between).
fn in_order(needle: &[String], hay: &[String]) -> bool {
    let mut rest = hay.iter();
    needle.iter().all(|w| rest.any(|h| h == w))
}

/// The table colour of the entry whose words appear, in order, among the words of `name`; the
/// entry with the most words wins, the first listed among equals. `None` when nothing matches.
pub fn color_for_name(name: &str) -> Option<[f32; 3]> {
    let words = words_of(name);
    let mut best: Option<&Entry> = None;
    for entry in table() {
        if in_order(&entry.words, &words) && best.is_none_or(|b| entry.words.len() > b.words.len())
        {
            best = Some(entry);
        }
    }
    best.map(|e| e.color)
}

/// A structure's colour: the file's own, else by anatomical name, else a distinct palette colour
/// chosen by `index` (the model's position in the list).
pub fn structure_color(name: &str, file_color: Option<[f32; 3]>, index: usize) -> [f32; 3] {
    file_color
        .or_else(|| color_for_name(name))
        .unwrap_or_else(|| distinct_colors(index + 1)[index])
}

/// The colour (sRGB in `0..=1`) of an embedded phantom's part, by anatomical class: skin beige,
/// fat yellow, muscle red, bone ivory, marrow ochre, vessel dark red, brain pink, ventricles
/// (CSF) light blue, disc blue-grey. Accepts a part name or a model name (`"femur 1"`); unknown
/// names get a neutral grey.
pub fn class_color(part_name: &str) -> [f32; 3] {
    let name = part_name.to_ascii_lowercase();
    let has = |words: &[&str]| words.iter().any(|w| name.contains(w));
    if has(&["marrow"]) {
        [0.80, 0.55, 0.25]
    } else if has(&["ventricle", "csf"]) {
        [0.55, 0.75, 0.95]
    } else if has(&["vessel", "artery", "vein", "popliteal"]) {
        [0.55, 0.07, 0.09]
    } else if has(&["disc", "disk"]) {
        [0.55, 0.62, 0.72]
    } else if has(&["skin"]) {
        [0.93, 0.76, 0.62]
    } else if has(&["fat"]) {
        [0.97, 0.86, 0.38]
    } else if has(&["muscle", "quadriceps", "vastus", "rectus"]) {
        [0.72, 0.20, 0.18]
    } else if has(&["brain", "cerebr", "cortex"]) {
        [0.93, 0.63, 0.66]
    } else if has(&[
        "bone", "femur", "tibia", "patella", "fibula", "skull", "vertebra", "spine",
    ]) {
        [0.95, 0.92, 0.80]
    } else {
        [0.70, 0.70, 0.70]
    }
}

/// `count` colours that are easy to tell apart (golden-angle hues, moderate saturation), for
/// models loaded without a colour.
pub fn distinct_colors(count: usize) -> Vec<[f32; 3]> {
    (0..count)
        .map(|i| {
            let hue = (0.08 + i as f32 * 0.381_966) % 1.0;
            hsv_to_rgb(hue, 0.45, 0.9)
        })
        .collect()
}

fn hsv_to_rgb(h: f32, s: f32, v: f32) -> [f32; 3] {
    let h6 = h * 6.0;
    let sector = h6.floor() as i32 % 6;
    let f = h6 - h6.floor();
    let (p, q, t) = (v * (1.0 - s), v * (1.0 - s * f), v * (1.0 - s * (1.0 - f)));
    match sector {
        0 => [v, t, p],
        1 => [q, v, p],
        2 => [p, v, t],
        3 => [p, q, v],
        4 => [t, p, v],
        _ => [v, p, q],
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rgb(c: [f32; 3]) -> [u8; 3] {
        c.map(|v| (v * 255.0).round() as u8)
    }

    #[test]
    fn the_shipped_table_parses() {
        assert!(table().len() > 50);
        assert!(parse("a 1 2").is_err());
        assert!(parse("a 1 2 300").unwrap_err().contains("line 1"));
    }

    #[test]
    fn names_match_whole_words_in_order_and_the_longest_entry_wins() {
        let hippocampus = color_for_name("left hippocampus").map(rgb);
        assert_eq!(hippocampus, Some([220, 216, 20]));
        let horn = color_for_name("temporal horn of left lateral ventricle").map(rgb);
        assert_eq!(horn, Some([88, 106, 215]));
        let cerebellar = color_for_name("white matter of left hemisphere of cerebellum").map(rgb);
        assert_eq!(cerebellar, Some([194, 195, 164]));
        assert_eq!(
            color_for_name("white matter").map(rgb),
            Some([250, 250, 210])
        );
        assert_eq!(
            color_for_name("VHF_Left_Bone_Tibia_smooth").map(rgb),
            Some([241, 214, 145])
        );
        // Whole words only: "skinny" is not skin, "eyeball" is not "eye".
        assert_eq!(color_for_name("skinny widget"), None);
        assert_eq!(color_for_name("part 3"), None);
    }

    #[test]
    fn file_colours_come_first_and_unknown_names_get_distinct_colours() {
        assert_eq!(
            structure_color("left hippocampus", Some([0.1, 0.2, 0.3]), 0),
            [0.1, 0.2, 0.3]
        );
        let a = structure_color("widget", None, 0);
        let b = structure_color("gadget", None, 1);
        assert_ne!(a, b);
    }

    #[test]
    fn distinct_colors_differ() {
        let colors = distinct_colors(6);
        for i in 0..6 {
            for j in 0..i {
                let d: f32 = (0..3).map(|k| (colors[i][k] - colors[j][k]).abs()).sum();
                assert!(
                    d > 0.1,
                    "{i} and {j} look alike: {:?} {:?}",
                    colors[i],
                    colors[j]
                );
            }
        }
    }
}
