//! The session field of rulers ([`crate::scene::ruler`]), kept apart from the rest of the session
//! format:
//!
//! ```json
//! "rulers": [{"a": [0, 0, 0], "b": [10, 0, 0]}]
//! ```
//!
//! Optional: a file without it (every file written before rulers existed) has none, and a file
//! without rulers is written without the field. At most [`MAX_RULERS`] rulers; every coordinate
//! is finite with magnitude at most [`crate::io::MAX_ABS_COORDINATE`]. Errors name the ruler.

use glam::DVec3;
use serde::{Deserialize, Serialize};

use crate::io::MAX_ABS_COORDINATE;
use crate::scene::ruler::Ruler;

/// Most rulers in one session (far above what a person measures by hand).
pub const MAX_RULERS: usize = 1_000;

/// One ruler as stored: its two ends in file units.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct RulerEntry {
    pub a: [f64; 3],
    pub b: [f64; 3],
}

/// Checks the count and coordinates (at parse time, before anything is built).
pub fn check(entries: &[RulerEntry]) -> anyhow::Result<()> {
    if entries.len() > MAX_RULERS {
        anyhow::bail!(
            "rulers: {} rulers, more than the limit of {MAX_RULERS}",
            entries.len()
        );
    }
    for (i, entry) in entries.iter().enumerate() {
        for (end, point) in [("a", entry.a), ("b", entry.b)] {
            if point
                .iter()
                .any(|v| !v.is_finite() || v.abs() > MAX_ABS_COORDINATE)
            {
                anyhow::bail!(
                    "ruler {i}: {end} {point:?} is not finite or beyond ±{MAX_ABS_COORDINATE}"
                );
            }
        }
    }
    Ok(())
}

/// The scene's rulers from the stored entries.
pub fn from_entries(entries: &[RulerEntry]) -> anyhow::Result<Vec<Ruler>> {
    check(entries)?;
    Ok(entries
        .iter()
        .map(|e| Ruler {
            a: DVec3::from_array(e.a),
            b: DVec3::from_array(e.b),
        })
        .collect())
}

/// The entries that store `rulers`.
pub fn entries(rulers: &[Ruler]) -> Vec<RulerEntry> {
    rulers
        .iter()
        .map(|r| RulerEntry {
            a: r.a.to_array(),
            b: r.b.to_array(),
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rulers_round_trip_and_bad_ones_are_named() {
        let rulers = vec![Ruler {
            a: DVec3::new(1.0, 2.0, 3.0),
            b: DVec3::new(-4.0, 5.5, 6.0),
        }];
        assert_eq!(from_entries(&entries(&rulers)).unwrap(), rulers);
        let bad = [RulerEntry {
            a: [0.0; 3],
            b: [f64::NAN, 0.0, 0.0],
        }];
        let e = from_entries(&bad).unwrap_err().to_string();
        assert!(e.starts_with("ruler 0: b"), "{e}");
        let many = vec![
            RulerEntry {
                a: [0.0; 3],
                b: [1.0; 3]
            };
            MAX_RULERS + 1
        ];
        assert!(check(&many).unwrap_err().to_string().contains("limit"));
    }
}
