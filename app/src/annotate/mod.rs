//! Annotations drawn into exported images, egui-free so the CLI and the window's exports draw
//! the same: text from a real font renderer ([`text`]), structure labels placed without overlap
//! ([`layout`]) with leaders ending where the structure is seen ([`visible`]), the scale bar
//! ([`scale_bar`]) and the orientation marker's geometry ([`orientation`]), put together by
//! [`labelled`]; [`picture`] renders a scene and draws the annotations chosen over it;
//! [`rulers`] draws the scene's saved rulers; [`risk_legend`] the risk map's legend, and renders
//! pictures with it.

pub mod labelled;
pub mod layout;
pub mod orientation;
pub mod picture;
pub mod risk_legend;
pub mod rulers;
pub mod scale_bar;
pub mod text;
pub mod visible;
