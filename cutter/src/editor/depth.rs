//! The editor's depth: the wheel over the cutter, the depth field, the default depth of a new
//! cutter, and what the cutter reaches. The rules are [`Rules`]' (see the editor's module docs);
//! the depth edits themselves are [`crate::edits`]'.

use glam::DVec2;

use super::{Editor, EditorResponse, Rules};
use crate::cutter::{CutKind, Cutter};
use crate::edits::{self, DepthTarget};
use crate::reach::{self, Reached};

impl Editor {
    /// The cutter's depth: the leading plane's, which the planes it rolls out take (None without
    /// a cutter).
    pub fn depth(&self) -> Option<f64> {
        Some(self.cutter.as_ref()?.leading().depth())
    }

    /// Gives every plane of the cutter the depth `depth` (the cutter panel's field), as one
    /// undoable action, checked like every edit. True when the cutter changed.
    pub fn set_depth(&mut self, depth: f64) -> bool {
        if self.is_dragging() {
            return false;
        }
        let Some(cutter) = &self.cutter else {
            return false;
        };
        let same = |d: f64| (d - depth).abs() <= 1e-12 * depth.abs();
        if !depth.is_finite() || cutter.planes.iter().all(|p| same(p.depth())) {
            return false;
        }
        match edits::set_depth(cutter, DepthTarget::All, depth, self.settings.delta) {
            Some(c) if self.accepts(&c, "the depth") => {
                self.commit(Some(c));
                true
            }
            Some(_) => false,
            None => {
                self.note = Some("the depth cannot be set there: planes would cross".to_string());
                false
            }
        }
    }

    /// The structures the cutter reaches through its target, nearest first ([`reach::reached`];
    /// empty without obstacles or a cutter).
    pub fn reached(&self) -> Vec<Reached> {
        match (&self.cutter, &self.obstacles) {
            (Some(c), Some(o)) => reach::reached(c, o.as_ref()),
            _ => Vec::new(),
        }
    }

    /// The name of an obstacle structure (for the status line).
    pub fn obstacle_name(&self, structure: usize) -> Option<String> {
        self.obstacles.as_ref().map(|o| o.name(structure))
    }

    /// True when the pixel is over any part of the cutter (the wheel changes its depth there).
    pub fn is_over_cutter(&self, px: DVec2) -> bool {
        self.over_cutter(px)
    }

    /// A freshly initialised cutter at the default depth of its rules: under [`Rules::Reach`]
    /// deep enough to reach the first obstacle behind the target ([`reach::default_depth`],
    /// kept in [`Editor::reach`]); unchanged under [`Rules::Delta`] and for wedges (a wedge's
    /// back reaches into the target on its own rule).
    pub(super) fn at_default_depth(&mut self, cutter: Cutter) -> Cutter {
        if self.settings.rules != Rules::Reach || cutter.kind == CutKind::Wedge {
            return cutter;
        }
        let fronts: Vec<_> = cutter
            .planes
            .iter()
            .map(|p| (p.front_top, p.front_bottom))
            .collect();
        let direction = cutter.planes[0].back_direction();
        let reach = reach::default_depth(
            &self.surface(),
            self.obstacles.as_deref(),
            &fronts,
            direction,
            self.settings.delta,
        );
        let mut deep = cutter.clone();
        for p in &mut deep.planes {
            *p = p.with_depth(reach.depth);
        }
        if deep.sanity_check().is_err() {
            return cutter;
        }
        self.reach = Some(reach);
        deep
    }

    pub(super) fn wheel(
        &mut self,
        px: DVec2,
        notches: f64,
        ctrl: bool,
        alt: bool,
    ) -> EditorResponse {
        let mut response = EditorResponse {
            cursor: self.hint(self.pick(px)),
            ..Default::default()
        };
        if self.is_dragging() || notches == 0.0 || !notches.is_finite() {
            return response;
        }
        let Some(cutter) = &self.cutter else {
            return response;
        };
        let over = self.over_cutter(px);
        let delta = self.settings.delta;
        let edited = match self.settings.rules {
            Rules::Delta => {
                let plane = if over {
                    self.selected.or_else(|| self.plane_under(px))
                } else {
                    None
                };
                if ctrl {
                    plane.and_then(|i| edits::rotate_plane(cutter, i, notches))
                } else {
                    let target = match plane {
                        Some(i) => DepthTarget::Plane(i),
                        None => DepthTarget::All,
                    };
                    edits::change_depth(cutter, target, notches, delta)
                }
            }
            Rules::Reach if !over => None,
            Rules::Reach if ctrl => self
                .selected
                .or_else(|| self.plane_under(px))
                .and_then(|i| edits::rotate_plane(cutter, i, notches)),
            Rules::Reach => {
                let target = if alt {
                    match self.nearest_plane(px) {
                        Some(i) => DepthTarget::Plane(i),
                        None => return response,
                    }
                } else {
                    DepthTarget::All
                };
                edits::scale_depth(cutter, target, notches, delta)
            }
        };
        if let Some(c) = edited.filter(|c| self.accepts(c, "the edit")) {
            self.commit(Some(c));
            response.changed = true;
        }
        response
    }
}
