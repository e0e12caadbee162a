//! One undo history for the whole window: scene changes and cutter edits interleaved in the order
//! the user made them, so Ctrl+Z always undoes the most recent thing whatever it was.
//!
//! Scene changes (load, remove, colour, opacity, style, visibility, "Remove All Cut Geometry") are
//! stored as snapshots `S` (the app keeps meshes behind `Arc`, so a snapshot is cheap). Cutter
//! edits are owned by the editor, which keeps its own undo stack; the history records only that
//! one happened ([`Step::Editor`]) and the app forwards undo/redo of such a step to the editor.
//! Doing anything new clears the redo side, as everywhere else.

/// One undoable step.
#[derive(Clone, Debug)]
pub enum Step<S> {
    /// A scene change: the state before and after it.
    Scene { label: String, before: S, after: S },
    /// An edit recorded by the cutter editor's own undo stack.
    Editor { label: String },
}

impl<S> Step<S> {
    /// What the Edit menu shows ("Undo colour change").
    pub fn label(&self) -> &str {
        match self {
            Step::Scene { label, .. } | Step::Editor { label } => label,
        }
    }
}

/// What the app must do to perform an undo or redo.
#[derive(Debug, PartialEq)]
pub enum Apply<'a, S> {
    /// Replace the scene state with this snapshot.
    Scene(&'a S),
    /// Call the editor's undo (for an undo) or redo (for a redo).
    Editor,
}

/// Undo and redo stacks with a size limit (oldest steps are forgotten first).
#[derive(Debug)]
pub struct History<S> {
    /// Steps that can be undone, oldest first, each with its number ([`History::last_number`]).
    done: Vec<(u64, Step<S>)>,
    /// Steps that can be redone, most recently undone last.
    undone: Vec<(u64, Step<S>)>,
    /// At most this many steps are kept in `done`.
    limit: usize,
    /// Steps recorded so far: the next step's number.
    recorded: u64,
}

impl<S> Default for History<S> {
    fn default() -> Self {
        History::new(200)
    }
}

impl<S> History<S> {
    pub fn new(limit: usize) -> Self {
        History {
            done: Vec::new(),
            undone: Vec::new(),
            limit: limit.max(1),
            recorded: 0,
        }
    }

    /// Records a scene change.
    pub fn push_scene(&mut self, label: impl Into<String>, before: S, after: S) {
        self.push(Step::Scene {
            label: label.into(),
            before,
            after,
        });
    }

    /// Records that the editor made an undoable edit.
    pub fn push_editor(&mut self, label: impl Into<String>) {
        self.push(Step::Editor {
            label: label.into(),
        });
    }

    fn push(&mut self, step: Step<S>) {
        self.undone.clear();
        self.done.push((self.recorded, step));
        self.recorded += 1;
        if self.done.len() > self.limit {
            let excess = self.done.len() - self.limit;
            self.done.drain(..excess);
        }
    }

    /// Moves the last step to the redo side and says how to undo it.
    pub fn undo(&mut self) -> Option<Apply<'_, S>> {
        let step = self.done.pop()?;
        self.undone.push(step);
        Some(match &self.undone.last()?.1 {
            Step::Scene { before, .. } => Apply::Scene(before),
            Step::Editor { .. } => Apply::Editor,
        })
    }

    /// Moves the last undone step back and says how to redo it.
    pub fn redo(&mut self) -> Option<Apply<'_, S>> {
        let step = self.undone.pop()?;
        self.done.push(step);
        Some(match &self.done.last()?.1 {
            Step::Scene { after, .. } => Apply::Scene(after),
            Step::Editor { .. } => Apply::Editor,
        })
    }

    /// Label of the step [`History::undo`] would undo.
    pub fn undo_label(&self) -> Option<&str> {
        self.done.last().map(|(_, s)| s.label())
    }

    /// Label of the step [`History::redo`] would redo.
    pub fn redo_label(&self) -> Option<&str> {
        self.undone.last().map(|(_, s)| s.label())
    }

    /// Forgets everything (a new scene or session was opened).
    pub fn clear(&mut self) {
        self.done.clear();
        self.undone.clear();
    }

    /// Every scene snapshot held, done and undone (to add what arrived after the steps were
    /// recorded, such as structures surfaced in the background, to each of them).
    pub fn scenes_mut(&mut self) -> impl Iterator<Item = &mut S> {
        self.scenes_after_mut(None)
    }

    /// The number of the step [`History::undo`] would undo: steps are numbered in the order
    /// they were recorded, and a number stays with its step through undo and redo.
    pub fn last_number(&self) -> Option<u64> {
        self.done.last().map(|(n, _)| *n)
    }

    /// The scene snapshots made from step `number` on: that step's after, and both of every
    /// later step's, done and undone (to add what arrived for that step to the scenes made
    /// since, and not to those before it).
    pub fn scenes_since_mut(&mut self, number: u64) -> impl Iterator<Item = &mut S> {
        self.scenes_after_mut(Some(number))
    }

    fn scenes_after_mut(&mut self, from: Option<u64>) -> impl Iterator<Item = &mut S> {
        self.done
            .iter_mut()
            .chain(self.undone.iter_mut())
            .flat_map(move |(n, step)| match step {
                Step::Scene { before, after, .. } => match from {
                    Some(from) if *n < from => Vec::new(),
                    Some(from) if *n == from => vec![after],
                    _ => vec![before, after],
                },
                Step::Editor { .. } => Vec::new(),
            })
    }

    /// Forgets editor steps only (the editor was replaced, its stack is gone).
    pub fn forget_editor_steps(&mut self) {
        self.done.retain(|(_, s)| matches!(s, Step::Scene { .. }));
        self.undone.retain(|(_, s)| matches!(s, Step::Scene { .. }));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn undo_and_redo_interleave_scene_and_editor_steps() {
        let mut h = History::<i32>::default();
        h.push_scene("set 1", 0, 1);
        h.push_editor("extrude");
        h.push_scene("set 2", 1, 2);
        assert_eq!(h.undo_label(), Some("set 2"));
        assert_eq!(h.undo(), Some(Apply::Scene(&1)));
        assert_eq!(h.undo(), Some(Apply::Editor));
        assert_eq!(h.undo(), Some(Apply::Scene(&0)));
        assert_eq!(h.undo(), None);
        assert_eq!(h.redo(), Some(Apply::Scene(&1)));
        assert_eq!(h.redo(), Some(Apply::Editor));
        assert_eq!(h.redo_label(), Some("set 2"));
        // A new step drops what could have been redone.
        h.push_scene("set 5", 1, 5);
        assert_eq!(h.redo(), None);
        assert_eq!(h.undo(), Some(Apply::Scene(&1)));
    }

    #[test]
    fn the_limit_forgets_the_oldest_steps() {
        let mut h = History::<i32>::new(2);
        h.push_scene("a", 0, 1);
        h.push_scene("b", 1, 2);
        h.push_scene("c", 2, 3);
        assert_eq!(h.undo(), Some(Apply::Scene(&2)));
        assert_eq!(h.undo(), Some(Apply::Scene(&1)));
        assert_eq!(h.undo(), None);
    }

    #[test]
    fn the_scenes_since_a_step_are_its_after_and_every_later_snapshot() {
        let mut h = History::<i32>::default();
        h.push_scene("a", 0, 1);
        h.push_scene("add", 1, 10);
        let add = h.last_number().unwrap();
        h.push_editor("e");
        h.push_scene("b", 10, 20);
        h.push_scene("c", 20, 30);
        assert_eq!(h.undo(), Some(Apply::Scene(&20)));
        for s in h.scenes_since_mut(add) {
            *s += 1000;
        }
        let mut all: Vec<i32> = h.scenes_mut().map(|s| *s).collect();
        all.sort();
        assert_eq!(all, [0, 1, 1, 1010, 1010, 1020, 1020, 1030]);
        // Numbers stay with their steps through undo and redo.
        assert_eq!(h.last_number(), Some(add + 2));
        assert_eq!(h.redo(), Some(Apply::Scene(&1030)));
        assert_eq!(h.last_number(), Some(add + 3));
    }

    #[test]
    fn forgetting_editor_steps_keeps_scene_steps() {
        let mut h = History::<i32>::default();
        h.push_scene("a", 0, 1);
        h.push_editor("e");
        h.forget_editor_steps();
        assert_eq!(h.undo(), Some(Apply::Scene(&0)));
        assert_eq!(h.undo(), None);
    }
}
