//! What hides the focus along each sampled ray, and how deep a cutter through each occluder
//! must reach there.
//!
//! In a cell whose ray meets the focus first at depth `d` (the point the eye would see if nothing
//! were in the way), an occluder hides the focus when the ray crosses it before `d`. A cutter
//! through that occluder, running along the rays from in front of it to a back face at depth
//! `b`, removes what lies between; the back face is a cut wall wherever it lies inside the
//! occluder. So the point at `d` is seen once `b` is past the occluder's last exit before `d`,
//! or, when the point lies inside the occluder (an odd number of crossings before `d`: a skin
//! around the brain), once `b` is past `d` itself: the wall then stands behind the focus. That
//! depth is the cell's **reach** for the occluder.

use crate::expose::abuffer::ABuffer;

/// Index of the focus among the meshes of the [`ABuffer`]; the occluders follow it.
pub const FOCUS: u32 = 0;

/// One occluder's hold on the focus.
#[derive(Clone, Debug, PartialEq)]
pub struct Occluder {
    /// The occluder's mesh index in the [`ABuffer`] (1 + its index among the occluders).
    pub mesh: u32,
    /// The cells where it hides the focus, each with its reach (see the module docs), by cell.
    pub hidden: Vec<(usize, f64)>,
}

/// The focus's depth in every cell and the occluders that hide it somewhere.
#[derive(Clone, Debug, Default)]
pub struct Occlusion {
    /// Per cell: the depth at which the ray first meets the focus (`f64::INFINITY` when it
    /// misses the focus).
    pub focus_depth: Vec<f64>,
    /// Every occluder that hides the focus in at least one cell, by mesh index.
    pub occluders: Vec<Occluder>,
}

impl Occlusion {
    /// Reads the occlusion of every cell of `buffer` (`cells` of them).
    pub fn of(buffer: &ABuffer, cells: usize) -> Occlusion {
        let mut focus_depth = vec![f64::INFINITY; cells];
        let mut hidden: Vec<(u32, usize, f64)> = Vec::new();
        // (mesh, crossings before the focus, depth of the last one) in the current cell.
        let mut seen: Vec<(u32, usize, f64)> = Vec::new();
        for (cell, depth) in focus_depth.iter_mut().enumerate() {
            let crossings = buffer.at(cell);
            let Some(first) = crossings.iter().find(|c| c.mesh == FOCUS) else {
                continue;
            };
            *depth = first.z;
            seen.clear();
            for c in crossings.iter().take_while(|c| c.z < first.z) {
                if c.mesh == FOCUS {
                    continue;
                }
                match seen.iter_mut().find(|s| s.0 == c.mesh) {
                    Some(s) => {
                        s.1 += 1;
                        s.2 = c.z;
                    }
                    None => seen.push((c.mesh, 1, c.z)),
                }
            }
            for &(mesh, count, last) in &seen {
                let reach = if count % 2 == 1 { first.z } else { last };
                hidden.push((mesh, cell, reach));
            }
        }
        hidden.sort_by_key(|h| (h.0, h.1));
        let mut occluders: Vec<Occluder> = Vec::new();
        for (mesh, cell, reach) in hidden {
            match occluders.last_mut() {
                Some(o) if o.mesh == mesh => o.hidden.push((cell, reach)),
                _ => occluders.push(Occluder {
                    mesh,
                    hidden: vec![(cell, reach)],
                }),
            }
        }
        Occlusion {
            focus_depth,
            occluders,
        }
    }

    /// Cells whose ray meets the focus.
    pub fn focus_cells(&self) -> usize {
        self.focus_depth.iter().filter(|d| d.is_finite()).count()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::expose::frame::ViewFrame;
    use glam::DVec3;

    #[test]
    fn a_shell_around_the_focus_reaches_past_it_and_a_plate_in_front_only_past_itself() {
        // The focus: a sphere of radius 5 at the origin; around it a closed sphere of radius 20
        // (the focus lies inside it); in front, a plate 2 thick whose far side is at y = -12.
        let focus = csg::testkit::geodesic_sphere(8, 5.0);
        let shell = csg::testkit::geodesic_sphere(8, 20.0);
        let plate = csg::testkit::cube(
            DVec3::new(-30.0, -14.0, -30.0),
            DVec3::new(30.0, -12.0, 30.0),
        );
        let frame = ViewFrame::oriented(
            DVec3::new(0.0, -100.0, 0.0),
            DVec3::Y,
            DVec3::X,
            DVec3::Z,
            &[],
        )
        .with_grid([-0.06, 0.06], [-0.06, 0.06], 21);
        let buffer = ABuffer::build(&frame, &[&focus, &shell, &plate], 1e-6);
        let occlusion = Occlusion::of(&buffer, frame.cells());
        let centre = frame.index(10, 10);
        let d = occlusion.focus_depth[centre];
        assert!((d - 95.0).abs() < 0.1, "{d}");
        assert_eq!(occlusion.occluders.len(), 2);
        let reach = |o: &Occluder| o.hidden.iter().find(|h| h.0 == centre).unwrap().1;
        assert_eq!(
            reach(&occlusion.occluders[0]),
            d,
            "inside the shell: past the focus"
        );
        assert!(
            (reach(&occlusion.occluders[1]) - 88.0).abs() < 1e-9,
            "the plate's far side"
        );
        assert_eq!(
            occlusion.occluders[0].hidden.len(),
            occlusion.focus_cells(),
            "the shell hides the focus everywhere"
        );
    }
}
