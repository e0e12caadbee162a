//! Where structure labels go: two columns along the image's left and right edges, each label
//! at the height of its structure when there is room, pushed down (then up) just enough that no
//! two labels overlap, with a leader line from the label's inner edge to a point of the
//! structure. Labels are sorted by the height of their point within a column, so leaders do not
//! cross each other there. A label that cannot fit in its column (too many for the image's
//! height) is left out rather than drawn over another.

/// An axis-aligned rectangle in pixels (top-left corner and size).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Rect {
    pub x: f32,
    pub y: f32,
    pub w: f32,
    pub h: f32,
}

impl Rect {
    /// Whether the two rectangles share interior area.
    pub fn overlaps(&self, other: &Rect) -> bool {
        self.x < other.x + other.w
            && other.x < self.x + self.w
            && self.y < other.y + other.h
            && other.y < self.y + self.h
    }
}

/// A structure to label: its text box size and the point of it the leader ends on.
#[derive(Clone, Debug, PartialEq)]
pub struct LabelRequest {
    pub text: String,
    /// Text box size in pixels (padding included).
    pub size: [f32; 2],
    /// The point of the structure (pixels).
    pub anchor: [f32; 2],
}

/// A placed label.
#[derive(Clone, Debug, PartialEq)]
pub struct PlacedLabel {
    /// Index into the requests.
    pub request: usize,
    pub rect: Rect,
    /// From the label's inner edge to the anchor.
    pub leader: [[f32; 2]; 2],
}

/// Places `requests` in an image of `size` pixels, inside `margin` of its edges and above a band
/// of `bottom_reserved` pixels (kept for the scale bar and orientation marker), with `gap` pixels
/// at least between labels of one column.
pub fn place(
    requests: &[LabelRequest],
    size: [f32; 2],
    margin: f32,
    gap: f32,
    bottom_reserved: f32,
) -> Vec<PlacedLabel> {
    let top = margin;
    let bottom = size[1] - margin - bottom_reserved;
    let mut placed = Vec::new();
    for left in [true, false] {
        let mut column: Vec<usize> = (0..requests.len())
            .filter(|&i| (requests[i].anchor[0] < size[0] * 0.5) == left)
            .filter(|&i| requests[i].size[0] + 2.0 * margin <= size[0] * 0.5)
            .collect();
        column.sort_by(|&a, &b| requests[a].anchor[1].total_cmp(&requests[b].anchor[1]));
        // Drop the labels that cannot fit (the ones farthest down first keeps the order simple).
        while !column.is_empty() {
            let needed: f32 = column.iter().map(|&i| requests[i].size[1]).sum::<f32>()
                + gap * (column.len() - 1) as f32;
            if needed <= bottom - top {
                break;
            }
            column.pop();
        }
        let mut ys = stack(requests, &column, top, bottom, gap);
        // Leaders of neighbouring labels that cross: swap the two labels' places (anchors at
        // different depths into the image can cross when sorted by height alone).
        let x_of = |i: usize| {
            if left {
                margin + requests[i].size[0]
            } else {
                size[0] - margin - requests[i].size[0]
            }
        };
        for _ in 0..4 * column.len() {
            let mut swapped = false;
            for k in 0..column.len().saturating_sub(1) {
                let (a, b) = (column[k], column[k + 1]);
                let leader = |i: usize, y: f32| {
                    [[x_of(i), y + requests[i].size[1] * 0.5], requests[i].anchor]
                };
                if segments_cross(leader(a, ys[k]), leader(b, ys[k + 1])) {
                    column.swap(k, k + 1);
                    ys = stack(requests, &column, top, bottom, gap);
                    swapped = true;
                }
            }
            if !swapped {
                break;
            }
        }
        for (k, &i) in column.iter().enumerate() {
            let r = &requests[i];
            let x = if left {
                margin
            } else {
                size[0] - margin - r.size[0]
            };
            let rect = Rect {
                x,
                y: ys[k],
                w: r.size[0],
                h: r.size[1],
            };
            let edge_x = if left { rect.x + rect.w } else { rect.x };
            placed.push(PlacedLabel {
                request: i,
                rect,
                leader: [[edge_x, rect.y + rect.h * 0.5], r.anchor],
            });
        }
    }
    placed.sort_by_key(|p| p.request);
    placed
}

/// Heights of the labels of `column` (in that order): each at its anchor's height or just below
/// the previous one, then those pushed past `bottom` moved up just enough, keeping `gap`.
fn stack(requests: &[LabelRequest], column: &[usize], top: f32, bottom: f32, gap: f32) -> Vec<f32> {
    let mut ys: Vec<f32> = Vec::with_capacity(column.len());
    let mut next_free = top;
    for &i in column {
        let r = &requests[i];
        let y = (r.anchor[1] - r.size[1] * 0.5).max(next_free);
        ys.push(y);
        next_free = y + r.size[1] + gap;
    }
    let mut limit = bottom;
    for k in (0..column.len()).rev() {
        let h = requests[column[k]].size[1];
        ys[k] = ys[k].min(limit - h);
        limit = ys[k] - gap;
    }
    ys
}

/// Whether segments `p` and `q` cross at a point inside both.
fn segments_cross(p: [[f32; 2]; 2], q: [[f32; 2]; 2]) -> bool {
    let side = |a: [f32; 2], b: [f32; 2], c: [f32; 2]| {
        (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
    };
    let d1 = side(q[0], q[1], p[0]);
    let d2 = side(q[0], q[1], p[1]);
    let d3 = side(p[0], p[1], q[0]);
    let d4 = side(p[0], p[1], q[1]);
    d1 * d2 < 0.0 && d3 * d4 < 0.0
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A small deterministic generator (no test depends on a random seed).
    fn lcg(state: &mut u64) -> f32 {
        *state = state
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (*state >> 40) as f32 / (1u64 << 24) as f32
    }

    #[test]
    fn no_two_labels_overlap_and_leaders_reach_their_anchors() {
        let mut state = 7;
        for round in 0..200 {
            let count = 1 + round % 25;
            let size = [
                400.0 + 600.0 * lcg(&mut state),
                300.0 + 500.0 * lcg(&mut state),
            ];
            let requests: Vec<LabelRequest> = (0..count)
                .map(|i| LabelRequest {
                    text: format!("s{i}"),
                    size: [40.0 + 100.0 * lcg(&mut state), 18.0 + 6.0 * lcg(&mut state)],
                    anchor: [size[0] * lcg(&mut state), size[1] * lcg(&mut state)],
                })
                .collect();
            let placed = place(&requests, size, 8.0, 4.0, 60.0);
            for (a, p) in placed.iter().enumerate() {
                let r = p.rect;
                assert!(r.x >= 8.0 - 1e-3 && r.x + r.w <= size[0] - 8.0 + 1e-3);
                assert!(
                    r.y >= 8.0 - 1e-3 && r.y + r.h <= size[1] - 68.0 + 1e-3,
                    "{r:?}"
                );
                assert_eq!(p.leader[1], requests[p.request].anchor);
                for q in &placed[a + 1..] {
                    assert!(!p.rect.overlaps(&q.rect), "{:?} {:?}", p.rect, q.rect);
                }
            }
            // Few labels always fit: none is dropped.
            if count <= 6 && size[1] > 68.0 + 6.0 * 30.0 {
                assert_eq!(placed.len(), count, "round {round}");
            }
        }
    }

    #[test]
    fn a_label_with_room_sits_at_its_anchor_s_height_on_its_side() {
        let requests = vec![
            LabelRequest {
                text: "left".into(),
                size: [60.0, 20.0],
                anchor: [100.0, 200.0],
            },
            LabelRequest {
                text: "right".into(),
                size: [60.0, 20.0],
                anchor: [700.0, 300.0],
            },
        ];
        let placed = place(&requests, [800.0, 600.0], 10.0, 4.0, 0.0);
        assert_eq!(
            placed[0].rect,
            Rect {
                x: 10.0,
                y: 190.0,
                w: 60.0,
                h: 20.0
            }
        );
        assert_eq!(
            placed[1].rect,
            Rect {
                x: 730.0,
                y: 290.0,
                w: 60.0,
                h: 20.0
            }
        );
        assert_eq!(placed[0].leader[0], [70.0, 200.0]);
        assert_eq!(placed[1].leader[0], [730.0, 300.0]);
    }

    #[test]
    fn leaders_that_would_cross_swap_places() {
        // Right column. C sits by the column and pushes A's label down; A's anchor is deep in
        // the image and a little above B's: in height order A's leader would cross B's.
        let request = |anchor: [f32; 2]| LabelRequest {
            text: String::new(),
            size: [80.0, 20.0],
            anchor,
        };
        let requests = vec![
            request([705.0, 290.0]),
            request([400.0, 300.0]),
            request([600.0, 305.0]),
        ];
        let placed = place(&requests, [800.0, 600.0], 10.0, 4.0, 0.0);
        assert_eq!(placed.len(), 3);
        for a in 0..3 {
            for b in a + 1..3 {
                assert!(
                    !segments_cross(placed[a].leader, placed[b].leader),
                    "{a} {b}"
                );
                assert!(!placed[a].rect.overlaps(&placed[b].rect));
            }
        }
        assert!(
            placed[1].rect.y > placed[2].rect.y,
            "the deep anchor's label went below"
        );
    }
}
