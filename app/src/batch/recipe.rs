//! The recipe of a batch (`cutaway-batch/1`): what to do with every case folder. Paths in it are
//! relative to the case folder (the volume, the image) or to the recipe's folder (nothing yet).
//!
//! ```json
//! {
//!   "format": "cutaway-batch/1",
//!   "volume": "segmentation.nii.gz",
//!   "image": "ct.nii.gz",
//!   "structures": ["liver", "portal vein"],
//!   "view": "anterior",
//!   "expose": {"focus": "portal vein", "margin": 3},
//!   "outputs": {
//!     "png": {"width": 800, "height": 600, "labels": true},
//!     "turntable": {"frames": 24, "width": 320, "height": 240},
//!     "glb": true,
//!     "html": true,
//!     "metrics": {"critical": ["aorta"]}
//!   }
//! }
//! ```

use std::path::Path;

use serde::{Deserialize, Serialize};

/// The `format` value.
pub const FORMAT: &str = "cutaway-batch/1";

#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Recipe {
    pub format: String,
    /// The label volume in each case folder (a file name or a folder of masks; `*` matches any
    /// run of characters, the first match in name order is used).
    pub volume: String,
    /// The intensity image in each case folder, shown on the cut walls.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub image: Option<String>,
    /// The structures shown (model names; none given: all).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub structures: Vec<String>,
    /// The view: anterior, posterior, left, right, superior or inferior.
    #[serde(default = "anterior")]
    pub view: String,
    /// The cutaway: open the view onto this structure (`cutaway expose`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub expose: Option<ExposeStep>,
    #[serde(default)]
    pub outputs: Outputs,
}

fn anterior() -> String {
    "anterior".to_owned()
}

#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ExposeStep {
    pub focus: String,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub margin: Option<f64>,
}

#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Outputs {
    /// `picture.png` (also the gallery's thumbnail); written unless `false`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub png: Option<PngOutput>,
    /// `turntable.gif`: an orbit around the cut.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub turntable: Option<TurntableOutput>,
    /// `scene.glb`.
    #[serde(default)]
    pub glb: bool,
    /// `scene.html`: the self-contained web page.
    #[serde(default)]
    pub html: bool,
    /// What the metrics row measures besides the removal (the exposure of the expose focus is
    /// always measured).
    #[serde(default)]
    pub metrics: MetricsOutput,
}

#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PngOutput {
    #[serde(default = "default_width")]
    pub width: u32,
    #[serde(default = "default_height")]
    pub height: u32,
    /// Structure names with leader lines, a scale bar and the orientation marker.
    #[serde(default)]
    pub labels: bool,
}

impl Default for PngOutput {
    fn default() -> PngOutput {
        PngOutput {
            width: default_width(),
            height: default_height(),
            labels: false,
        }
    }
}

fn default_width() -> u32 {
    800
}

fn default_height() -> u32 {
    600
}

#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TurntableOutput {
    #[serde(default = "default_frames")]
    pub frames: u32,
    #[serde(default = "default_turn_side")]
    pub width: u32,
    #[serde(default = "default_turn_side")]
    pub height: u32,
    #[serde(default = "default_delay")]
    pub delay_ms: u32,
}

fn default_frames() -> u32 {
    24
}

fn default_turn_side() -> u32 {
    320
}

fn default_delay() -> u32 {
    80
}

#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MetricsOutput {
    /// Structures whose distance to the cut walls is measured.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub critical: Vec<String>,
}

impl Recipe {
    /// Parses and checks a recipe's text (errors say what is wrong; the caller names the file).
    pub fn parse(text: &str) -> anyhow::Result<Recipe> {
        let recipe: Recipe =
            serde_json::from_str(text).map_err(|e| anyhow::anyhow!("not a valid recipe: {e}"))?;
        if recipe.format != FORMAT {
            anyhow::bail!("format is {:?}, expected {FORMAT:?}", recipe.format);
        }
        crate::scene::ViewPreset::ALL
            .iter()
            .find(|p| p.label().eq_ignore_ascii_case(&recipe.view))
            .ok_or_else(|| {
                anyhow::anyhow!(
                    "view {:?}: expected anterior, posterior, left, right, superior or inferior",
                    recipe.view
                )
            })?;
        if let Some(png) = &recipe.outputs.png {
            for (what, v) in [("width", png.width), ("height", png.height)] {
                if !(1..=16384).contains(&v) {
                    anyhow::bail!("outputs.png.{what} {v} is outside 1..16384");
                }
            }
        }
        if let Some(turn) = &recipe.outputs.turntable {
            for (what, v) in [("width", turn.width), ("height", turn.height)] {
                if !(1..=4096).contains(&v) {
                    anyhow::bail!("outputs.turntable.{what} {v} is outside 1..4096");
                }
            }
        }
        Ok(recipe)
    }

    /// Reads and checks the recipe at `path` (errors name it).
    pub fn read(path: &Path) -> anyhow::Result<Recipe> {
        use anyhow::Context as _;
        let text = crate::io::bounded::read_text(path, crate::io::bounded::JSON_MAX_BYTES)
            .with_context(|| path.display().to_string())?;
        Recipe::parse(&text).with_context(|| path.display().to_string())
    }

    /// The picture options (a picture is always made: it is the gallery's thumbnail).
    pub fn png(&self) -> PngOutput {
        self.outputs.png.clone().unwrap_or_default()
    }

    /// A digest of the recipe: a case done with another recipe is done again.
    pub fn digest(&self) -> String {
        let text = serde_json::to_string(self).unwrap_or_default();
        // FNV-1a 64: stable across runs and platforms, enough to tell recipes apart.
        let mut hash: u64 = 0xcbf2_9ce4_8422_2325;
        for b in text.bytes() {
            hash ^= u64::from(b);
            hash = hash.wrapping_mul(0x0000_0100_0000_01b3);
        }
        format!("{hash:016x}")
    }
}

/// Whether `name` matches `pattern` (`*` any run of characters, everything else literal).
pub fn matches(pattern: &str, name: &str) -> bool {
    let parts: Vec<&str> = pattern.split('*').collect();
    if parts.len() == 1 {
        return pattern == name;
    }
    let (first, last) = (parts[0], parts[parts.len() - 1]);
    if !name.starts_with(first) || name.len() < first.len() + last.len() || !name.ends_with(last) {
        return false;
    }
    let mut rest = &name[first.len()..name.len() - last.len()];
    for part in &parts[1..parts.len() - 1] {
        match rest.find(part) {
            Some(at) => rest = &rest[at + part.len()..],
            None => return false,
        }
    }
    true
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn patterns_match_as_globs() {
        assert!(matches("seg.nii.gz", "seg.nii.gz"));
        assert!(!matches("seg.nii.gz", "seg.nii"));
        assert!(matches("*.nii.gz", "a.nii.gz"));
        assert!(matches("*labels*", "chest_labels.nii.gz"));
        assert!(!matches("*.nrrd", "a.nii.gz"));
        assert!(!matches("a*a", "a"));
    }

    #[test]
    fn recipes_are_checked() {
        let ok = r#"{"format":"cutaway-batch/1","volume":"*.nrrd"}"#;
        let recipe = Recipe::parse(ok).unwrap();
        assert_eq!(recipe.view, "anterior");
        assert_eq!(recipe.png().width, 800);
        let bad_view = r#"{"format":"cutaway-batch/1","volume":"a","view":"sideways"}"#;
        assert!(format!("{:#}", Recipe::parse(bad_view).unwrap_err()).contains("sideways"));
        let unknown = r#"{"format":"cutaway-batch/1","volume":"a","volum":"b"}"#;
        assert!(format!("{:#}", Recipe::parse(unknown).unwrap_err()).contains("volum"));
        let other = r#"{"format":"cutaway-session/2","volume":"a"}"#;
        assert!(Recipe::parse(other).is_err());
        assert_ne!(
            Recipe::parse(ok).unwrap().digest(),
            Recipe::parse(r#"{"format":"cutaway-batch/1","volume":"*.nii"}"#)
                .unwrap()
                .digest()
        );
    }
}
