//! Undo and redo over whole snapshots of the edited state.
//!
//! Edits change the live state freely; [`History::settle`] records one undo
//! step when the state differs from the last recorded one and no gesture is
//! in progress, so a drag of many frames is a single step. Each step keeps
//! a name for the menu ("Undo θ"), given by whoever records it.

/// Undo/redo stacks for a cloneable, comparable state `T`.
#[derive(Debug)]
pub struct History<T> {
    /// The state as of the last recorded step.
    recorded: T,
    /// Older states, newest last, each with the name of the step that left it.
    undo: Vec<(T, String)>,
    /// States undone, the next redo last, each with its step's name.
    redo: Vec<(T, String)>,
}

/// How many steps are kept; the oldest are dropped beyond this.
const MAX_STEPS: usize = 500;

impl<T: Clone + PartialEq> History<T> {
    /// A history whose starting point is `state`, with nothing to undo.
    pub fn new(state: &T) -> Self {
        Self {
            recorded: state.clone(),
            undo: Vec::new(),
            redo: Vec::new(),
        }
    }

    /// Records `current` as one step if it differs from the last recorded
    /// state and `gesture_in_progress` is false; true when a step was recorded.
    pub fn settle(&mut self, current: &T, gesture_in_progress: bool) -> bool {
        self.settle_named(current, gesture_in_progress, |_, _| String::new())
    }

    /// [`History::settle`], naming the step by `name(before, after)`.
    pub fn settle_named(
        &mut self,
        current: &T,
        gesture_in_progress: bool,
        name: impl FnOnce(&T, &T) -> String,
    ) -> bool {
        if gesture_in_progress || *current == self.recorded {
            return false;
        }
        let name = name(&self.recorded, current);
        let previous = std::mem::replace(&mut self.recorded, current.clone());
        self.undo.push((previous, name));
        if self.undo.len() > MAX_STEPS {
            self.undo.remove(0);
        }
        self.redo.clear();
        true
    }

    /// Steps `current` back; an edit not yet recorded is recorded first, so it
    /// is what gets undone. False when there is nothing to undo.
    pub fn undo(&mut self, current: &mut T) -> bool {
        self.settle(current, false);
        let Some((previous, name)) = self.undo.pop() else {
            return false;
        };
        self.redo
            .push((std::mem::replace(&mut self.recorded, previous), name));
        *current = self.recorded.clone();
        true
    }

    /// Re-applies the last undone step; false when there is none.
    pub fn redo(&mut self, current: &mut T) -> bool {
        if *current != self.recorded {
            // A new edit since the undo: the redo branch is gone.
            self.settle(current, false);
            return false;
        }
        let Some((next, name)) = self.redo.pop() else {
            return false;
        };
        self.undo
            .push((std::mem::replace(&mut self.recorded, next), name));
        *current = self.recorded.clone();
        true
    }

    /// True when [`History::undo`] would change something.
    pub fn can_undo(&self, current: &T) -> bool {
        !self.undo.is_empty() || *current != self.recorded
    }

    /// The name of the step [`History::undo`] would undo, when it is a
    /// recorded step with a name (not an edit still under way).
    pub fn undo_name(&self, current: &T) -> Option<&str> {
        let (_, name) = self.undo.last().filter(|_| *current == self.recorded)?;
        (!name.is_empty()).then_some(name.as_str())
    }

    /// The name of the step [`History::redo`] would redo, if any.
    pub fn redo_name(&self, current: &T) -> Option<&str> {
        let (_, name) = self.redo.last().filter(|_| *current == self.recorded)?;
        (!name.is_empty()).then_some(name.as_str())
    }

    /// True when [`History::redo`] would change something.
    pub fn can_redo(&self, current: &T) -> bool {
        !self.redo.is_empty() && *current == self.recorded
    }
}

#[cfg(test)]
mod tests {
    use super::History;

    #[test]
    fn a_gesture_of_many_changes_is_one_step() {
        let mut value = 0;
        let mut history = History::new(&value);
        for frame in 1..=10 {
            value = frame;
            assert!(!history.settle(&value, true), "nothing recorded mid-drag");
        }
        assert!(history.settle(&value, false));
        assert!(history.undo(&mut value));
        assert_eq!(value, 0);
        assert!(!history.undo(&mut value), "one step only");
    }

    #[test]
    fn each_step_keeps_its_name_for_undo_and_then_for_redo() {
        let mut value = 1;
        let mut history = History::new(&value);
        let name = |a: &i32, b: &i32| format!("{a} to {b}");
        value = 2;
        assert!(history.settle_named(&value, false, name));
        value = 5;
        assert_eq!(
            history.undo_name(&value),
            None,
            "an edit under way has no name yet"
        );
        assert!(history.settle_named(&value, false, name));
        assert_eq!(history.undo_name(&value), Some("2 to 5"));
        assert!(history.undo(&mut value));
        assert_eq!(
            (history.undo_name(&value), history.redo_name(&value)),
            (Some("1 to 2"), Some("2 to 5"))
        );
        assert!(history.redo(&mut value));
        assert_eq!((value, history.undo_name(&value)), (5, Some("2 to 5")));
    }

    #[test]
    fn undo_then_redo_round_trips_every_step() {
        let mut value = 'a';
        let mut history = History::new(&value);
        for next in ['b', 'c', 'd'] {
            value = next;
            history.settle(&value, false);
        }
        for expected in ['c', 'b', 'a'] {
            assert!(history.undo(&mut value));
            assert_eq!(value, expected);
        }
        for expected in ['b', 'c', 'd'] {
            assert!(history.redo(&mut value));
            assert_eq!(value, expected);
        }
        assert!(!history.redo(&mut value));
    }

    #[test]
    fn undo_during_an_unrecorded_edit_undoes_that_edit() {
        let mut value = 1;
        let mut history = History::new(&value);
        value = 2; // still being dragged
        assert!(history.can_undo(&value));
        assert!(history.undo(&mut value));
        assert_eq!(value, 1);
        assert!(history.redo(&mut value));
        assert_eq!(value, 2);
    }

    #[test]
    fn a_new_edit_after_undo_discards_the_redo_branch() {
        let mut value = 1;
        let mut history = History::new(&value);
        value = 2;
        history.settle(&value, false);
        history.undo(&mut value);
        value = 3;
        assert!(!history.can_redo(&value));
        assert!(!history.redo(&mut value));
        assert_eq!(value, 3);
        assert!(history.undo(&mut value));
        assert_eq!(value, 1);
    }
}
