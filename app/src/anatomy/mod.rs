//! The anatomy the binary carries: the embedded default scene (the SPL head atlas), the
//! synthetic phantoms, and the colours of structures by anatomical name.

pub mod assets;
pub mod colors;
pub mod default_scene;
pub mod examples;
pub mod phantom;
