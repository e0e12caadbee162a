//! How the scene is looked at, free of egui and wgpu so that the window, headless renders and
//! labelled exports agree: the patient's axes in world space and the radiological view presets
//! ([`orientation`]), the orientation marker's axes as a camera projects them ([`marker`]), the
//! length unit of the data and the defaults that follow from the target's size ([`units`]; which
//! target, and the scalpel's lengths kept in step with it: [`target`]), and
//! framing (zoom to fit, zoom to a selection: [`fit`]), and the camera moves the pointer makes
//! (orbit, pan, zoom, centring: [`camera_controls`]).

pub mod camera_controls;
pub mod fit;
pub mod marker;
pub mod orientation;
pub mod target;
pub mod units;

pub use orientation::{Orientation, ViewPreset};
pub use units::{LengthUnit, SizeDefaults};

#[cfg(test)]
mod session_tests;
