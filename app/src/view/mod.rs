//! How the scene is looked at, free of egui so that the window, headless renders and labelled
//! exports agree: the scene made into the renderer's frame ([`frame`]) and rendered headless
//! with its cut ([`headless`]), the orientation marker's axes as a camera projects them
//! ([`marker`]), framing (zoom to fit, zoom to a selection: [`fit`]), and the camera moves the
//! pointer makes (orbit, pan, zoom, centring: [`camera_controls`]). The patient's axes, the view
//! presets and the length unit are the scene's (`crate::scene::orientation`,
//! `crate::scene::units`).

pub mod camera_controls;
pub mod fit;
pub mod frame;
pub mod headless;
pub mod marker;

pub use headless::{RenderPngOptions, render_mode, render_png, render_with, render_with_preview};
