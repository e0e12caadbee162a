//! The structures of a mask folder as they are surfaced, shown in file order.
//!
//! The workers surface a folder's masks in about file order, each finishing when it finishes.
//! A structure's place in the scene (and its `index`, by which a session names it) is its rank
//! among the folder's masks that have voxels, in file order: known for a mask only once every
//! earlier file is done. So the outcomes are held until every earlier one has come and released
//! strictly in order; a model, once in the scene, never moves, and cutters made meanwhile keep
//! their targets.

use std::collections::BTreeMap;

use crate::io::Model;

/// Outcomes of a folder's files, released in file order (see the module doc).
#[derive(Default)]
pub struct InOrder {
    /// Outcomes that came before an earlier file's: file number → the structure, None for an
    /// empty mask.
    pending: BTreeMap<usize, Option<Model>>,
    /// The next file number to release.
    next: usize,
    /// Structures released so far.
    released: usize,
}

impl InOrder {
    pub fn new() -> InOrder {
        InOrder::default()
    }

    /// Takes file number `file`'s outcome (its structure, None for an empty mask).
    pub fn put(&mut self, file: usize, model: Option<Model>) {
        self.pending.insert(file, model);
    }

    /// The structures whose every earlier file is done, in file order, each with `index` its
    /// rank among the folder's structures.
    pub fn ready(&mut self) -> Vec<Model> {
        let mut out = Vec::new();
        while let Some(outcome) = self.pending.remove(&self.next) {
            self.next += 1;
            if let Some(mut model) = outcome {
                model.index = self.released;
                self.released += 1;
                out.push(model);
            }
        }
        out
    }

    /// Structures released so far.
    pub fn released(&self) -> usize {
        self.released
    }

    /// Outcomes held back, waiting on an earlier file.
    pub fn waiting(&self) -> usize {
        self.pending.len()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn model(name: &str) -> Option<Model> {
        Some(Model::part(name.to_owned(), None, csg::Mesh::default()))
    }

    /// Out-of-order outcomes come out in file order once the gap before them closes; empty
    /// masks take no index.
    #[test]
    fn outcomes_are_released_in_file_order_with_their_rank() {
        let mut order = InOrder::new();
        order.put(1, model("b"));
        order.put(3, model("d"));
        assert!(order.ready().is_empty(), "file 0 is not done");
        assert_eq!(order.waiting(), 2);
        order.put(0, model("a"));
        let first: Vec<(String, usize)> = order
            .ready()
            .into_iter()
            .map(|m| (m.name, m.index))
            .collect();
        assert_eq!(first, [("a".to_owned(), 0), ("b".to_owned(), 1)]);
        order.put(2, None);
        order.put(4, model("e"));
        let rest: Vec<(String, usize)> = order
            .ready()
            .into_iter()
            .map(|m| (m.name, m.index))
            .collect();
        assert_eq!(rest, [("d".to_owned(), 2), ("e".to_owned(), 3)]);
        assert_eq!((order.released(), order.waiting()), (4, 0));
    }
}
