//! `--image`, `--window` and `--display`, shared by the commands that show the intensity image
//! (`open`, `render`, `export`).

use std::path::Path;
use std::sync::Arc;

use anyhow::Context as _;

use crate::io::intensity::Window;
use crate::scene::Scene;
use crate::scene::{ImageLayer, WallDisplay};

/// Reads `image` (if given) into the scene's image layer, checking that it meets the models, then
/// applies `window` and `display` to whatever image the scene has.
pub fn apply(
    scene: &mut Scene,
    image: Option<&Path>,
    window: Option<&str>,
    display: Option<&str>,
) -> anyhow::Result<()> {
    if let Some(path) = image {
        let read = crate::io::volume::intensity::read_image(path)?;
        crate::io::intensity::check_overlap(&read, scene.bbox())
            .with_context(|| path.display().to_string())?;
        scene.image = Some(ImageLayer::new(Arc::new(read)));
    }
    if window.is_none() && display.is_none() {
        return Ok(());
    }
    let Some(layer) = scene.image.as_mut() else {
        anyhow::bail!("--window and --display need an image (--image, or a session with one)");
    };
    if let Some(text) = window {
        layer.window = Window::parse(text, &layer.image)
            .with_context(|| layer.image.source.display().to_string())?;
    }
    if let Some(text) = display {
        layer.display = WallDisplay::parse(text)
            .ok_or_else(|| anyhow::anyhow!("--display {text:?} is not image, blend or color"))?;
    }
    Ok(())
}
