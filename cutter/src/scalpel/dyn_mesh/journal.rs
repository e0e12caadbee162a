//! The mesh's journal: every write goes through a setter here that records the old value, so
//! any run of edits rolls back to a [`Mark`], and every write also logs the vertices it changed,
//! so the live opening can recompute only around them ([`DynMesh::edits_since`]).

use glam::DVec3;

use super::DynMesh;

/// Entries of the edit log kept before it is emptied (a reader then starts over).
const EDITS_KEPT: usize = 1 << 22;

/// One undoable write.
#[derive(Clone, Copy, Debug)]
pub(super) enum Change {
    Tri(u32, [u32; 3]),
    Twin(u32, u32),
    VertHe(u32, u32),
    NextCopy(u32, u32),
    Pos(u32, DVec3),
}

/// A point in the edit history to roll back to.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Mark {
    positions: usize,
    triangles: usize,
    journal: usize,
}

impl DynMesh {
    /// The current point in history.
    pub fn mark(&self) -> Mark {
        Mark {
            positions: self.positions.len(),
            triangles: self.triangles.len(),
            journal: self.journal.len(),
        }
    }

    /// Undoes every edit made since `mark` (which must not have been rolled back past already).
    pub fn rollback(&mut self, mark: Mark) {
        while self.journal.len() > mark.journal {
            match self.journal.pop() {
                Some(Change::Tri(t, v)) => {
                    let now = self.triangles[t as usize];
                    self.log_edits(&now);
                    self.log_edits(&v);
                    self.triangles[t as usize] = v;
                }
                Some(Change::Twin(h, v)) => {
                    self.log_triangle(h / 3);
                    self.twin[h as usize] = v;
                }
                Some(Change::VertHe(x, v)) => {
                    self.log_edits(&[x]);
                    self.vert_he[x as usize] = v;
                }
                Some(Change::NextCopy(x, v)) => {
                    let now = self.next_copy[x as usize];
                    self.log_edits(&[x, now, v]);
                    self.next_copy[x as usize] = v;
                }
                Some(Change::Pos(x, p)) => {
                    self.log_edits(&[x]);
                    self.positions[x as usize] = p;
                }
                None => break,
            }
        }
        for t in mark.triangles..self.triangles.len() {
            self.log_triangle(t as u32);
        }
        let removed: Vec<u32> = (mark.positions as u32..self.positions.len() as u32).collect();
        self.log_edits(&removed);
        self.positions.truncate(mark.positions);
        self.vert_he.truncate(mark.positions);
        self.next_copy.truncate(mark.positions);
        self.singular.truncate(mark.positions);
        self.floor.truncate(mark.positions);
        self.triangles.truncate(mark.triangles);
        self.wall_tri.truncate(mark.triangles);
        self.twin.truncate(3 * mark.triangles);
    }

    /// Triangles written or created since `mark` (sorted, unique): what a step touched.
    pub(crate) fn touched_since(&self, mark: Mark) -> Vec<u32> {
        let mut out: Vec<u32> = (mark.triangles as u32..self.triangles.len() as u32).collect();
        for c in &self.journal[mark.journal.min(self.journal.len())..] {
            match *c {
                Change::Tri(t, _) => out.push(t),
                Change::Twin(h, _) => out.push(h / 3),
                _ => {}
            }
        }
        out.retain(|&t| (t as usize) < self.triangles.len());
        out.sort_unstable();
        out.dedup();
        out
    }

    /// Where the edit log ends now: pass it to [`DynMesh::edits_since`] later.
    pub fn edit_cursor(&self) -> usize {
        self.edits_dropped + self.edits.len()
    }

    /// The vertices changed since `cursor` (an [`DynMesh::edit_cursor`]): moved, re-linked,
    /// copied, created or removed (ids at or past [`DynMesh::vertex_count`] were removed), with
    /// repeats. `None` when the log no longer reaches back that far.
    pub fn edits_since(&self, cursor: usize) -> Option<&[u32]> {
        let from = cursor.checked_sub(self.edits_dropped)?;
        self.edits.get(from..)
    }

    pub(super) fn log_edits(&mut self, vertices: &[u32]) {
        if self.edits.len() + vertices.len() > EDITS_KEPT {
            self.edits_dropped += self.edits.len();
            self.edits.clear();
        }
        self.edits.extend_from_slice(vertices);
    }

    pub(super) fn log_triangle(&mut self, t: u32) {
        if let Some(&tri) = self.triangles.get(t as usize) {
            self.log_edits(&tri);
        }
    }

    /// Forgets the undo history (nothing before now can be rolled back any more).
    pub fn forget_history(&mut self) {
        self.journal.clear();
    }

    pub(super) fn set_tri(&mut self, t: u32, tri: [u32; 3]) {
        let old = self.triangles[t as usize];
        self.journal.push(Change::Tri(t, old));
        self.log_edits(&old);
        self.log_edits(&tri);
        self.triangles[t as usize] = tri;
    }

    pub(super) fn set_twin(&mut self, h: u32, g: u32) {
        let old = self.twin[h as usize];
        if old != g {
            self.journal.push(Change::Twin(h, old));
            self.log_triangle(h / 3);
            self.twin[h as usize] = g;
        }
    }

    pub(super) fn set_vert_he(&mut self, v: u32, h: u32) {
        let old = self.vert_he[v as usize];
        if old != h {
            self.journal.push(Change::VertHe(v, old));
            self.log_edits(&[v]);
            self.vert_he[v as usize] = h;
        }
    }

    pub(super) fn set_next_copy(&mut self, v: u32, n: u32) {
        let old = self.next_copy[v as usize];
        self.journal.push(Change::NextCopy(v, old));
        self.log_edits(&[v, old, n]);
        self.next_copy[v as usize] = n;
    }

    /// Moves vertex `v` (groove floor vertices: the deeper cut at a crossing and the tapered ends;
    /// surface vertices moved onto the cut, `scalpel::relocate`).
    pub(crate) fn set_pos(&mut self, v: u32, p: DVec3) {
        let old = self.positions[v as usize];
        self.journal.push(Change::Pos(v, old));
        self.log_edits(&[v]);
        self.positions[v as usize] = p;
    }
}
