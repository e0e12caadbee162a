//! The session's `"image"` object: the intensity image shown on the walls, kept apart from the
//! rest of the session format so that it can grow on its own.
//!
//! ```json
//! "image": {"path": "CT.nrrd", "window": [40, 400], "on": ["walls", "slices"], "display": "image"}
//! ```
//! `path` is relative to the session file (or absolute); `window` is `[level, width]` in the
//! image's units (absent: soft tissue for a CT, else the 1st–99th percentile); `on` lists where
//! the image is shown (`walls`: the cut walls; `slices`: slices and ribbons; absent: both);
//! `display` is `image`, `blend` (half structure colour) or `color` (structure colour only;
//! absent: `image`). A session without `"image"` shows none, as before.

use std::path::{Path, PathBuf};
use std::sync::Arc;

use anyhow::Context as _;
use serde::{Deserialize, Serialize};

use crate::io::intensity::Window;
use crate::scene::Scene;
use crate::scene::{ImageLayer, WallDisplay};

#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ImageEntry {
    pub path: PathBuf,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub window: Option<[f64; 2]>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub on: Option<Vec<String>>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub display: Option<String>,
}

/// Reads the image an entry names (`folder`: the session file's folder) and checks that it meets
/// the scene's models.
pub fn load(entry: &ImageEntry, folder: &Path, scene: &Scene) -> anyhow::Result<ImageLayer> {
    let path = if entry.path.is_absolute() {
        entry.path.clone()
    } else {
        folder.join(&entry.path)
    };
    let image = crate::io::volume::intensity::read_image(&path)?;
    crate::io::intensity::check_overlap(&image, scene.bbox())
        .with_context(|| path.display().to_string())?;
    let mut layer = ImageLayer::new(Arc::new(image));
    apply(entry, &mut layer).context("image")?;
    Ok(layer)
}

/// Applies an entry's window, places and display to `layer`.
pub fn apply(entry: &ImageEntry, layer: &mut ImageLayer) -> anyhow::Result<()> {
    if let Some([level, width]) = entry.window {
        if !(level.is_finite() && width.is_finite() && width > 0.0) {
            anyhow::bail!("window [{level}, {width}] needs a finite level and a positive width");
        }
        layer.window = Window { level, width };
    }
    if let Some(on) = &entry.on {
        layer.on_walls = false;
        layer.on_slices = false;
        for place in on {
            match place.as_str() {
                "walls" => layer.on_walls = true,
                "slices" | "ribbons" => layer.on_slices = true,
                other => anyhow::bail!("on: {other:?} is not \"walls\" or \"slices\""),
            }
        }
    }
    if let Some(display) = &entry.display {
        layer.display = WallDisplay::parse(display).ok_or_else(|| {
            anyhow::anyhow!("display {display:?} is not \"image\", \"blend\" or \"color\"")
        })?;
    }
    Ok(())
}

/// The entry describing `layer`, its path relative to `folder` where possible.
pub fn entry(layer: &ImageLayer, folder: &Path) -> ImageEntry {
    let mut on = Vec::new();
    if layer.on_walls {
        on.push("walls".to_string());
    }
    if layer.on_slices {
        on.push("slices".to_string());
    }
    ImageEntry {
        path: crate::session::paths::relative_path(&layer.image.source, folder),
        window: Some([layer.window.level, layer.window.width]),
        on: Some(on),
        display: Some(layer.display.name().to_string()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DAffine3;

    fn layer() -> ImageLayer {
        let image =
            crate::io::intensity::IntensityImage::from_fn([2, 2, 2], DAffine3::IDENTITY, |p| {
                p.x as f32
            });
        ImageLayer::new(Arc::new(image))
    }

    #[test]
    fn entry_round_trips_and_bad_fields_are_named() {
        let mut l = layer();
        l.window = Window {
            level: -600.0,
            width: 1500.0,
        };
        l.on_slices = false;
        l.display = WallDisplay::Blend;
        let e = entry(&l, Path::new("."));
        let json = serde_json::to_string(&e).unwrap();
        let back: ImageEntry = serde_json::from_str(&json).unwrap();
        let mut m = layer();
        apply(&back, &mut m).unwrap();
        assert_eq!(m.window, l.window);
        assert_eq!(
            (m.on_walls, m.on_slices, m.display),
            (true, false, WallDisplay::Blend)
        );

        let minimal: ImageEntry = serde_json::from_str(r#"{"path": "CT.nrrd"}"#).unwrap();
        let mut m = layer();
        apply(&minimal, &mut m).unwrap();
        assert_eq!(
            (m.on_walls, m.on_slices, m.display),
            (true, true, WallDisplay::Image)
        );

        for (bad, says) in [
            (r#"{"path": "a", "window": [0, 0]}"#, "positive width"),
            (r#"{"path": "a", "on": ["floor"]}"#, "floor"),
            (r#"{"path": "a", "display": "x-ray"}"#, "x-ray"),
        ] {
            let e: ImageEntry = serde_json::from_str(bad).unwrap();
            let err = apply(&e, &mut layer()).unwrap_err().to_string();
            assert!(err.contains(says), "{err}");
        }
    }
}
