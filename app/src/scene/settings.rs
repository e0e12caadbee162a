//! The Rendering menu's settings of a scene.

/// Stereo output of the renderer.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Stereo {
    #[default]
    None,
    /// Red/blue anaglyph: left eye in red, right eye in blue.
    Anaglyph,
}

impl Stereo {
    pub fn as_str(self) -> &'static str {
        match self {
            Stereo::None => "none",
            Stereo::Anaglyph => "anaglyph",
        }
    }

    pub fn parse(text: &str) -> Option<Stereo> {
        match text {
            "none" => Some(Stereo::None),
            "anaglyph" => Some(Stereo::Anaglyph),
            _ => None,
        }
    }
}

/// The Rendering menu.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RenderSettings {
    /// sRGB background colour with straight alpha; alpha 0 exports a transparent PNG.
    /// Default: white, opaque.
    pub background: [f32; 4],
    /// Supersampling (2×2) when true. Default: true.
    pub antialias: bool,
    /// Default: none.
    pub stereo: Stereo,
}

impl Default for RenderSettings {
    fn default() -> RenderSettings {
        RenderSettings {
            background: [1.0, 1.0, 1.0, 1.0],
            antialias: true,
            stereo: Stereo::None,
        }
    }
}
