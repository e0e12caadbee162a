//! `--critical NAME…`, `--risk-mm NEAR,FAR` and `--no-risk`, shared by the commands that draw
//! or export the cut walls (`render`, `turntable`, `export`): the risk map of the session
//! ([`crate::scene::risk`]) replaced, adjusted or switched off for this run. `--critical` names
//! structures as `metrics --critical` does, and an unknown name is refused listing the
//! structures.

use crate::scene::Scene;
use crate::scene::risk::RiskSettings;

#[derive(Clone, Debug, Default, clap::Args)]
pub struct RiskArgs {
    /// Colour the cut walls by their distance to these structures (model names): red within the
    /// near distance, graded to the far one (replaces the session's critical structures).
    #[arg(long, num_args = 1.., value_name = "NAME")]
    pub critical: Vec<String>,
    /// The risk map's distances in mm: red within NEAR, graded to FAR (default: the session's,
    /// else 2,10).
    #[arg(long, value_name = "NEAR,FAR")]
    pub risk_mm: Option<String>,
    /// Draw the walls without the session's risk map.
    #[arg(long, conflicts_with_all = ["critical", "risk_mm"])]
    pub no_risk: bool,
}

/// Applies `args` to the scene's risk map.
pub fn apply(scene: &mut Scene, args: &RiskArgs) -> anyhow::Result<()> {
    if args.no_risk {
        scene.risk.shown = false;
        return Ok(());
    }
    if !args.critical.is_empty() {
        // Named as the model list names them (`organ 1` also finds a single-region `organ`).
        let mut critical = Vec::new();
        for name in &args.critical {
            let i = crate::scene::names::model_named(scene, name, "")?;
            critical.push(scene.models[i].model.name.clone());
        }
        scene.risk.critical = critical;
        scene.risk.shown = true;
    }
    if let Some(text) = &args.risk_mm {
        let (near, far) = parse_mm(text)?;
        if scene.risk.critical.is_empty() {
            anyhow::bail!(
                "--risk-mm needs critical structures (--critical, or a session with a risk map)"
            );
        }
        scene.risk.near_mm = near;
        scene.risk.far_mm = far;
        scene.risk.shown = true;
    }
    scene
        .risk
        .check()
        .map_err(|e| anyhow::anyhow!("--risk-mm: {e}"))
}

/// `NEAR,FAR` in mm.
fn parse_mm(text: &str) -> anyhow::Result<(f64, f64)> {
    let bad = || anyhow::anyhow!("--risk-mm {text:?} is not NEAR,FAR in mm (as in 2,10)");
    let (near, far) = text.split_once(',').ok_or_else(bad)?;
    let near: f64 = near.trim().parse().map_err(|_| bad())?;
    let far: f64 = far.trim().parse().map_err(|_| bad())?;
    let settings = RiskSettings {
        near_mm: near,
        far_mm: far,
        ..RiskSettings::default()
    };
    settings
        .check()
        .map_err(|e| anyhow::anyhow!("--risk-mm {text:?}: {e}"))?;
    Ok((near, far))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scene() -> Scene {
        crate::test_support::named_spheres(&["skin", "vessel"])
    }

    #[test]
    fn critical_names_turn_the_map_on_and_unknown_ones_are_refused() {
        let mut s = scene();
        let args = RiskArgs {
            critical: vec!["vessel".into()],
            risk_mm: Some("1.5, 8".into()),
            no_risk: false,
        };
        apply(&mut s, &args).unwrap();
        assert!(s.risk.is_on());
        assert_eq!((s.risk.near_mm, s.risk.far_mm), (1.5, 8.0));

        let err = apply(
            &mut scene(),
            &RiskArgs {
                critical: vec!["liver".into()],
                ..Default::default()
            },
        )
        .unwrap_err()
        .to_string();
        assert!(
            err.contains("'liver'") && err.contains("skin, vessel"),
            "{err}"
        );

        for bad in ["2", "a,b", "10,2", "-1,5"] {
            let err = parse_mm(bad).unwrap_err().to_string();
            assert!(err.contains("--risk-mm"), "{err}");
        }
        let err = apply(
            &mut scene(),
            &RiskArgs {
                risk_mm: Some("2,10".into()),
                ..Default::default()
            },
        )
        .unwrap_err()
        .to_string();
        assert!(err.contains("needs critical"), "{err}");
    }
}
