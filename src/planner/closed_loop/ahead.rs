//! A repair searched while the arm plays. Where the rest of the plan is valid for its first
//! controls and then stops being valid (or ends short of the goal), its ending is searched
//! from where the valid part ends: a state the model predicts, not the next observation.
//! So the arm need not wait for the search: it plays the valid part meanwhile, and the
//! repair is taken up at the first observation after the search is done *and* the controls
//! played since it began have lasted as long as it took, at the execution's pace. That is
//! robot time: an engine that simulates faster or slower than the clock does not change
//! when a robot would have had the repair. Where nothing valid is left to play first, the
//! arm waits for it, and the wait is what the re-plan's latency counts.

use super::{ClosedLoop, SearchFound, SearchRecord};
use crate::planning::path::PathControl;
use crate::scene::Scene;
use crate::state::State;
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

/// An ending searched from a state the model predicts: the controls found (or why none
/// were), and the time the search took (s, wall clock).
type Ending = (Result<Vec<PathControl>, String>, f64);

/// A repair's search running beside the arm ([`RepairAhead::begin`]).
pub(super) struct RepairAhead {
    /// The search's thread, until it is joined.
    searching: Option<JoinHandle<Ending>>,
    /// What it found, once joined.
    done: Option<Ending>,
    /// When the search began (wall clock).
    began: Instant,
    /// The rest after the control played as the search began, up to where the ending is
    /// searched from: the repair is these controls, less those played since, and the ending.
    prefix: Vec<PathControl>,
    /// Controls handed to the arm since the search began, the first included.
    played: usize,
    /// Their duration at the execution's pace (s).
    played_for: f64,
    /// The search on the record (its `seconds`, `waited` and `found` filled in when taken
    /// up).
    record: SearchRecord,
}

impl RepairAhead {
    /// Searches an ending from `end` (where the rest's valid part `valid` ends, as the
    /// model predicts it from `from`'s start) on a thread of its own, with `time` as a
    /// repair gets it ([`ClosedLoop::ending`]); `record` is the search as the record will
    /// show it. The caller hands `valid`'s first control to the arm next and tells
    /// [`RepairAhead::played`]. None where no thread could be started (then the caller
    /// searches as it would without one).
    pub(super) fn begin(
        closed_loop: &ClosedLoop,
        from: &Scene,
        (valid, end): (&[PathControl], &State),
        time: f64,
        index: usize,
        record: SearchRecord,
    ) -> Option<RepairAhead> {
        let (closed_loop, from, end) = (closed_loop.clone(), from.clone(), end.clone());
        let ending = move || closed_loop.ending(&from, &end, time, index);
        RepairAhead::searching(valid, ending, record)
    }

    /// [`RepairAhead::begin`] with the ending's search given.
    fn searching(
        valid: &[PathControl],
        ending: impl FnOnce() -> Result<Vec<PathControl>, String> + Send + 'static,
        record: SearchRecord,
    ) -> Option<RepairAhead> {
        let handle = std::thread::Builder::new()
            .name("repair-ahead".into())
            .spawn(move || {
                let began = Instant::now();
                let ending = ending();
                (ending, began.elapsed().as_secs_f64())
            })
            .ok()?;
        Some(RepairAhead {
            searching: Some(handle),
            done: None,
            began: Instant::now(),
            prefix: valid.get(1..).unwrap_or_default().to_vec(),
            played: 0,
            played_for: 0.0,
            record,
        })
    }

    /// A control of `seconds` (at the execution's pace) handed to the arm.
    pub(super) fn played(&mut self, seconds: f64) {
        self.played += 1;
        self.played_for += seconds;
    }

    /// Is the search done, and have the controls played since it began lasted as long?
    /// Where they have lasted longer than the wall clock has run since (an engine faster
    /// than the clock), the search gets up to that long to finish: a robot would have had
    /// what it finds in that time.
    pub(super) fn due(&mut self) -> bool {
        let robot_time = self.began + Duration::from_secs_f64(self.played_for);
        if let Some(handle) = &self.searching {
            while !handle.is_finished() && Instant::now() < robot_time {
                std::thread::sleep(Duration::from_millis(1));
            }
            if !handle.is_finished() {
                return false;
            }
            self.wait();
        }
        self.done
            .as_ref()
            .is_some_and(|(_, seconds)| *seconds <= self.played_for)
    }

    /// Waits for the search to end (a search that panicked found nothing, and says so).
    fn wait(&mut self) {
        if let Some(handle) = self.searching.take() {
            let ending = handle
                .join()
                .unwrap_or_else(|_| (Err("the repair's search panicked".to_string()), 0.0));
            self.done = Some(ending);
        }
    }

    /// The repair (the prefix less the controls played since the search began, then the
    /// ending), or why the search found none; and the search's record, `waited` the arm's
    /// wait for it in robot time (what it took beyond the controls played since it began:
    /// none where it was [`RepairAhead::due`]). Waits for the search if it runs.
    pub(super) fn take(mut self) -> (Result<Vec<PathControl>, String>, SearchRecord) {
        self.wait();
        let (ending, seconds) = self.done.take().expect("the search joined");
        let mut record = self.record.clone();
        record.seconds = seconds;
        record.waited = (seconds - self.played_for).max(0.0);
        record.found = match ending {
            Ok(_) => SearchFound::Repair,
            Err(_) => SearchFound::Nothing,
        };
        let played_since = self.played.saturating_sub(1).min(self.prefix.len());
        let repair = ending.map(|ending| [&self.prefix[played_since..], &ending].concat());
        (repair, record)
    }
}

impl Drop for RepairAhead {
    /// A search still running when the execution ends is waited for: it calls into OMPL,
    /// which must not be torn down under it when the process exits.
    fn drop(&mut self) {
        self.wait();
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::robot::EeAction;

    /// A control told apart from the others by its step count.
    fn control(steps: usize) -> PathControl {
        PathControl {
            action: EeAction::planar(0.0, 0.0, 0.0),
            steps,
        }
    }

    fn record() -> SearchRecord {
        SearchRecord {
            after_controls: 0,
            goal_distance: 0.1,
            rest_valid: 4,
            rest_ends: "ends short".into(),
            time: 2.0,
            seconds: 0.0,
            ahead: true,
            waited: 0.0,
            found: SearchFound::Nothing,
        }
    }

    /// A search of `seconds` (wall clock) that finds the ending `[control(99)]`, ahead of
    /// the valid part controls 1 to 4.
    fn ahead_of(seconds: f64) -> RepairAhead {
        let valid: Vec<PathControl> = (1..=4).map(control).collect();
        let ending = move || {
            std::thread::sleep(Duration::from_secs_f64(seconds));
            Ok(vec![control(99)])
        };
        RepairAhead::searching(&valid, ending, record()).unwrap()
    }

    fn steps(controls: &[PathControl]) -> Vec<usize> {
        controls.iter().map(|c| c.steps).collect()
    }

    #[test]
    fn a_repair_is_due_once_the_arm_has_played_for_as_long_as_it_searched() {
        let mut ahead = ahead_of(0.2);
        // One control of 10 ms handed to the arm: a robot would not have the repair yet.
        ahead.played(0.01);
        assert!(!ahead.due());
        // Two more, 0.5 s in all: by then a robot would have it (the test waits for it).
        ahead.played(0.24);
        ahead.played(0.25);
        assert!(ahead.due());
        let (repair, record) = ahead.take();
        // Controls 1 to 3 were played (control 1 as the search began): the repair is the
        // rest of the valid part, then the ending.
        assert_eq!(steps(&repair.unwrap()), [4, 99]);
        assert_eq!(record.found, SearchFound::Repair);
        assert!(record.seconds >= 0.2 && record.waited == 0.0, "{record:?}");
    }

    #[test]
    fn a_repair_found_before_its_time_waits_until_the_arm_has_played_as_long() {
        // The search is done at once, but the controls played since have lasted less than
        // it took: a robot (whose controls take their time) would not have it yet.
        let mut ahead = ahead_of(0.05);
        std::thread::sleep(Duration::from_secs_f64(0.1));
        ahead.played(0.01);
        assert!(!ahead.due());
        ahead.played(0.1);
        assert!(ahead.due());
    }

    #[test]
    fn with_nothing_left_to_play_the_arm_waits_what_the_search_took_beyond_its_controls() {
        let mut ahead = ahead_of(0.3);
        ahead.played(0.1);
        let (repair, record) = ahead.take();
        let waited = record.waited;
        assert!((0.2..0.5).contains(&waited), "{waited}");
        assert!((record.seconds - 0.1 - waited).abs() < 1e-9, "{record:?}");
        // One control played, the first of the valid part: the prefix is whole.
        assert_eq!(steps(&repair.unwrap()), [2, 3, 4, 99]);
    }

    #[test]
    fn a_search_that_panics_finds_nothing_and_says_so() {
        let valid = [control(1), control(2)];
        let ending = || -> Result<Vec<PathControl>, String> { panic!("a bug in the search") };
        let mut ahead = RepairAhead::searching(&valid, ending, record()).unwrap();
        ahead.played(0.1);
        let (repair, record) = ahead.take();
        assert!(repair.unwrap_err().contains("panicked"));
        assert_eq!(record.found, SearchFound::Nothing);
    }
}
