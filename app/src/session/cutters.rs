//! A session's cutter entries and the scene's cutters, converted both ways (the top-level
//! `cutters` and every variant's use the same conversion). This is the one place the contract's
//! kind names meet [`cutter::CutKind`] and the file's corner lists meet
//! [`cutter::BoundedPlane`]: the scene holds the `cutter` crate's cutter itself.

use glam::DVec3;
use serde::{Deserialize, Serialize};

use crate::scene::{CutterViews, SceneCutter, SubCutterSpec};
use cutter::subcutters::Placement;
use cutter::{BoundedPlane, CutDirection, CutKind, Cutter};

/// The scene cutter a session entry describes; errors name cutter `i`.
pub fn cutter_from_entry(i: usize, c: &CutterEntry) -> anyhow::Result<SceneCutter> {
    let kind = CutKind::from_name(&c.kind).ok_or_else(|| {
        anyhow::anyhow!(
            "cutter {i}: kind {:?} is not curving, straight or wedge",
            c.kind
        )
    })?;
    let sub = |what: &str, v: &Option<SubCutterEntry>| -> anyhow::Result<_> {
        let Some(v) = v else { return Ok(None) };
        let placement = Placement::from_name(&v.placement).ok_or_else(|| {
            anyhow::anyhow!(
                "cutter {i}: {what} placement {:?} is not even, planes or horizontal",
                v.placement
            )
        })?;
        Ok(Some(SubCutterSpec {
            count: v.count as usize,
            width: v.width,
            placement,
            relative: v.relative,
        }))
    };
    let direction = match c.direction.as_deref() {
        None => CutDirection::Normal,
        Some(name) => CutDirection::from_name(name).ok_or_else(|| {
            anyhow::anyhow!("cutter {i}: direction {name:?} is not view or normal")
        })?,
    };
    let levels = c.levels.unwrap_or(cutter::subdivision::DEFAULT_LEVELS);
    if levels > cutter::subdivision::MAX_LEVELS {
        anyhow::bail!(
            "cutter {i}: levels {levels} is more than the {} subdivision levels a smooth cutter can have",
            cutter::subdivision::MAX_LEVELS
        );
    }
    Ok(SceneCutter {
        target: c.target,
        cutter: Cutter {
            kind,
            smooth: c.smooth,
            levels,
            direction,
            planes: c
                .planes
                .iter()
                .map(|p| BoundedPlane::from_corners(p.map(DVec3::from_array)))
                .collect(),
        },
        views: CutterViews {
            cut: c.views.cut,
            transparency: c.views.transparency,
            ribbons: sub("ribbons", &c.views.ribbons)?,
            slices: sub("slices", &c.views.slices)?,
        },
    })
}

/// The session entry of a scene cutter.
pub fn cutter_entry(c: &SceneCutter) -> CutterEntry {
    let sub = |v: Option<SubCutterSpec>| {
        v.map(|v| SubCutterEntry {
            count: u32::try_from(v.count).unwrap_or(u32::MAX),
            width: v.width,
            placement: v.placement.name().to_string(),
            relative: v.relative,
        })
    };
    CutterEntry {
        target: c.target,
        kind: c.cutter.kind.name().to_string(),
        smooth: c.cutter.smooth,
        levels: Some(c.cutter.levels),
        direction: (c.cutter.direction == CutDirection::View)
            .then(|| CutDirection::View.name().to_string()),
        planes: c
            .cutter
            .planes
            .iter()
            .map(|p| p.corners().map(|v| v.to_array()))
            .collect(),
        views: ViewsEntry {
            cut: c.views.cut,
            transparency: c.views.transparency,
            ribbons: sub(c.views.ribbons),
            slices: sub(c.views.slices),
        },
    }
}

#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct CutterEntry {
    pub target: usize,
    /// `curving`, `straight` or `wedge`.
    #[serde(default = "curving")]
    pub kind: String,
    #[serde(default)]
    pub smooth: bool,
    /// Subdivision levels of a smooth cutter, 0 to 4 (the window's "Smoothness"); added later:
    /// a file without it means the default, 2.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub levels: Option<u32>,
    /// `view` or `normal`: which way the cutter's planes go (added later: a file without it
    /// means `normal`, how every earlier cutter was made; written only for `view`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub direction: Option<String>,
    pub planes: Vec<[[f64; 3]; 4]>,
    #[serde(default)]
    pub views: ViewsEntry,
}

#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ViewsEntry {
    #[serde(default = "yes")]
    pub cut: bool,
    #[serde(default)]
    pub transparency: Option<f32>,
    #[serde(default)]
    pub ribbons: Option<SubCutterEntry>,
    #[serde(default)]
    pub slices: Option<SubCutterEntry>,
}

impl Default for ViewsEntry {
    fn default() -> ViewsEntry {
        ViewsEntry {
            cut: true,
            transparency: None,
            ribbons: None,
            slices: None,
        }
    }
}

/// Ribbons or slices. `placement` and `relative` were added later: a file without them means
/// evenly spaced sub-cutters of an absolute width, as before.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SubCutterEntry {
    pub count: u32,
    pub width: f64,
    /// `even` (regular intervals along the path), `planes` (centred on each cutting plane) or
    /// `horizontal` (layers parallel to the surface at depth steps).
    #[serde(default = "even")]
    pub placement: String,
    /// `width` is the fraction of the spacing each sub-cutter fills instead of model units.
    #[serde(default)]
    pub relative: bool,
}

fn even() -> String {
    "even".to_string()
}

fn curving() -> String {
    "curving".to_string()
}

fn yes() -> bool {
    true
}

#[cfg(test)]
mod tests {
    use super::*;

    fn session(levels: &str) -> String {
        format!(
            r#"{{
          "format": "cutaway-session/2",
          "models": [],
          "cutters": [{{"target": 0, "kind": "curving", "smooth": true{levels},
                       "planes": [[[0,0,0],[0,1,0],[0,1,-1],[0,0,-1]],
                                  [[1,0,0],[1,1,0],[1,1,-1],[1,0,-1]]]}}]
        }}"#
        )
    }

    fn levels_of(text: &str) -> anyhow::Result<u32> {
        let file = crate::session::parse(text)?;
        cutter_from_entry(0, &file.cutters[0]).map(|c| c.cutter.levels)
    }

    #[test]
    fn session_cutter_levels_round_trip_and_old_files_get_the_default() {
        // A file written before the field: the default levels, written out from then on.
        let old = session("");
        assert_eq!(
            levels_of(&old).unwrap(),
            cutter::subdivision::DEFAULT_LEVELS
        );
        let file = crate::session::parse(&old).unwrap();
        let scene_cutter = cutter_from_entry(0, &file.cutters[0]).unwrap();
        let entry = cutter_entry(&scene_cutter);
        assert_eq!(entry.levels, Some(cutter::subdivision::DEFAULT_LEVELS));
        // Every level a user can pick survives a save and a load.
        for levels in 0..=cutter::subdivision::MAX_LEVELS {
            let text = session(&format!(r#", "levels": {levels}"#));
            let mut c =
                cutter_from_entry(0, &crate::session::parse(&text).unwrap().cutters[0]).unwrap();
            assert_eq!(c.cutter.levels, levels);
            c.views.cut = false;
            let saved = serde_json::to_string(&cutter_entry(&c)).unwrap();
            assert!(saved.contains(&format!(r#""levels":{levels}"#)), "{saved}");
            let back: CutterEntry = serde_json::from_str(&saved).unwrap();
            assert_eq!(cutter_from_entry(0, &back).unwrap(), c);
        }
        // More than a smooth cutter can have: one error naming the cutter and the value.
        let err = levels_of(&session(r#", "levels": 9"#)).unwrap_err();
        let msg = format!("{err:#}");
        assert!(
            msg.contains("cutter 0") && msg.contains("levels 9"),
            "{msg}"
        );
        let err = levels_of(&session(r#", "levels": -1"#)).unwrap_err();
        assert!(
            format!("{err:#}").contains("not a valid session"),
            "{err:#}"
        );
    }
}
