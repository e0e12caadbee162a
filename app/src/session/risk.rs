//! The session's `"risk"` object: the walls coloured by their distance to critical structures
//! ([`crate::scene::risk`]), kept apart from the rest of the format like `"image"`.
//!
//! ```json
//! "risk": {"critical": ["optic chiasm", "basilar artery"], "near_mm": 2, "far_mm": 10, "shown": true}
//! ```
//! `critical` names structures as the model list (and `metrics --critical`) names them; every
//! name must be a structure of the session, else the file is refused listing the structures.
//! `near_mm` (default 2) and `far_mm` (default 10) satisfy `0 ≤ near_mm < far_mm ≤ 1000`;
//! `shown` (default true) is false when the map is switched off but its critical set kept. A
//! session without `"risk"` colours no walls, as before; Cutaway writes the object only when a
//! structure is critical or a distance differs from its default.

use serde::{Deserialize, Serialize};

use crate::scene::Scene;
use crate::scene::risk::RiskSettings;

#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct RiskEntry {
    #[serde(default)]
    pub critical: Vec<String>,
    #[serde(default = "near")]
    pub near_mm: f64,
    #[serde(default = "far")]
    pub far_mm: f64,
    #[serde(default = "yes")]
    pub shown: bool,
}

fn near() -> f64 {
    RiskSettings::NEAR_MM
}
fn far() -> f64 {
    RiskSettings::FAR_MM
}
fn yes() -> bool {
    true
}

/// The settings an entry describes, checked against the scene's structures.
pub fn load(entry: &RiskEntry, scene: &Scene) -> anyhow::Result<RiskSettings> {
    // Named as the model list names them (`organ 1` also finds a single-region `organ`).
    let critical = entry
        .critical
        .iter()
        .map(|name| {
            crate::scene::names::model_named(scene, name, "")
                .map(|i| scene.models[i].model.name.clone())
        })
        .collect::<anyhow::Result<Vec<_>>>()?;
    let settings = RiskSettings {
        critical,
        near_mm: entry.near_mm,
        far_mm: entry.far_mm,
        shown: entry.shown,
    };
    settings.check().map_err(anyhow::Error::msg)?;
    Ok(settings)
}

/// The entry describing `settings`; `None` when they are the defaults with nothing critical.
pub fn entry(settings: &RiskSettings) -> Option<RiskEntry> {
    let unused = RiskSettings {
        critical: Vec::new(),
        ..settings.clone()
    } == RiskSettings::default();
    if settings.critical.is_empty() && unused {
        return None;
    }
    Some(RiskEntry {
        critical: settings.critical.clone(),
        near_mm: settings.near_mm,
        far_mm: settings.far_mm,
        shown: settings.shown,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scene() -> Scene {
        crate::test_support::named_spheres(&["skin", "optic chiasm"])
    }

    #[test]
    fn entry_round_trips_with_defaults_and_refuses_unknown_names() {
        let settings = RiskSettings {
            critical: vec!["optic chiasm".into()],
            near_mm: 1.5,
            far_mm: 8.0,
            shown: false,
        };
        let e = entry(&settings).expect("an entry");
        let json = serde_json::to_string(&e).unwrap();
        let back: RiskEntry = serde_json::from_str(&json).unwrap();
        assert_eq!(load(&back, &scene()).unwrap(), settings);

        let minimal: RiskEntry = serde_json::from_str(r#"{"critical": ["skin"]}"#).unwrap();
        let loaded = load(&minimal, &scene()).unwrap();
        assert_eq!(
            (loaded.near_mm, loaded.far_mm, loaded.shown),
            (2.0, 10.0, true)
        );
        assert_eq!(entry(&RiskSettings::default()), None);

        let unknown: RiskEntry = serde_json::from_str(r#"{"critical": ["liver"]}"#).unwrap();
        let err = load(&unknown, &scene()).unwrap_err().to_string();
        assert!(
            err.contains("'liver'") && err.contains("skin, optic chiasm"),
            "{err}"
        );
        let bad: RiskEntry = serde_json::from_str(r#"{"near_mm": 12}"#).unwrap();
        let err = load(&bad, &scene()).unwrap_err().to_string();
        assert!(err.contains("near_mm 12"), "{err}");
    }
}
