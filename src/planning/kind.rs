//! The planners pushplan runs, by one list of names: the CLI's `--planner` and
//! `--planners`, the plan file's `planner`, the benchmark logs and C++'s
//! `pushplan::PlannerKind` all use it.

use std::fmt;
use std::str::FromStr;

/// Push KPIECE's first restart budget: about 2 s of its search on the benchmark scenes
/// (BENCHMARKS.md, "Restarts").
const PUSH_KPIECE_RESTART_STEPS: u64 = 400_000;

/// Push KPIECE's patience before it falls back to PC RRT: about 3 s of its search in
/// dense clutter (BENCHMARKS.md, "Push KPIECE falls back to PC RRT").
const PUSH_KPIECE_FALLBACK_STEPS: u64 = 1_000_000;

/// A planner. C++'s `pushplan::PlannerKind` (`include/pushplan/pushplan.h`) is the same
/// type, value for value: the bridge passes it as is.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[repr(u8)]
pub enum PlannerKind {
    /// The whole-arm paper's physics-constrained RRT (PC RRT).
    PcRrt = 0,
    /// PC RRT with every object but the goal object a static obstacle (the paper's baseline).
    StaticRrt = 1,
    /// DARRT with the Transit and Push primitives (the paper's baseline).
    Darrt = 2,
    /// OMPL's KPIECE1 with uniform controls.
    Kpiece = 3,
    /// OMPL's EST.
    Est = 4,
    /// OMPL's PDST.
    Pdst = 5,
    /// OMPL's SST (asymptotically near-optimal: it uses the whole time limit).
    Sst = 6,
    /// DARRT with the PickPlace primitive beside Push (the paper's suggestion, Sec. V-A).
    DarrtPickPlace = 7,
    /// KPIECE1 whose controls mostly follow push headings (the planner's `PushHeading`):
    /// pushplan's own planner.
    PushKpiece = 8,
}

impl PlannerKind {
    /// Every planner, in the order the CLI lists them.
    pub const ALL: [PlannerKind; 9] = [
        PlannerKind::PushKpiece,
        PlannerKind::PcRrt,
        PlannerKind::StaticRrt,
        PlannerKind::Darrt,
        PlannerKind::Kpiece,
        PlannerKind::Est,
        PlannerKind::Pdst,
        PlannerKind::Sst,
        PlannerKind::DarrtPickPlace,
    ];

    /// The planner's name.
    pub fn name(self) -> &'static str {
        match self {
            PlannerKind::PcRrt => "pcrrt",
            PlannerKind::StaticRrt => "static",
            PlannerKind::Darrt => "darrt",
            PlannerKind::DarrtPickPlace => "darrt_pick",
            PlannerKind::Kpiece => "kpiece",
            PlannerKind::PushKpiece => "push_kpiece",
            PlannerKind::Est => "est",
            PlannerKind::Pdst => "pdst",
            PlannerKind::Sst => "sst",
        }
    }

    /// The name papers and plots use ("PC RRT", "KPIECE1", ...).
    pub fn paper_name(self) -> &'static str {
        match self {
            PlannerKind::PcRrt => "PC RRT",
            PlannerKind::StaticRrt => "Static RRT",
            PlannerKind::Darrt => "DARRT",
            PlannerKind::DarrtPickPlace => "DARRT + PickPlace",
            PlannerKind::Kpiece => "KPIECE1",
            PlannerKind::PushKpiece => "Push KPIECE",
            PlannerKind::Est => "EST",
            PlannerKind::Pdst => "PDST",
            PlannerKind::Sst => "SST",
        }
    }

    /// The planner's name in OMPL benchmark logs, without OMPL's `control_` prefix.
    pub fn ompl_name(self) -> &'static str {
        match self {
            PlannerKind::PcRrt => "PCRRT",
            PlannerKind::StaticRrt => "StaticRRT",
            PlannerKind::Darrt => "DARRT",
            PlannerKind::DarrtPickPlace => "DARRTPickPlace",
            PlannerKind::Kpiece => "KPIECE1",
            PlannerKind::PushKpiece => "PushKPIECE",
            PlannerKind::Est => "EST",
            PlannerKind::Pdst => "PDST",
            PlannerKind::Sst => "SST",
        }
    }

    /// The planner a benchmark log names (`control_PCRRT`, `DARRT`, ...).
    pub fn from_ompl_name(name: &str) -> Option<PlannerKind> {
        let name = name.strip_prefix("control_").unwrap_or(name);
        PlannerKind::ALL.into_iter().find(|k| k.ompl_name() == name)
    }

    /// Does it search on after its first solution until the time limit (asymptotically
    /// near-optimal)? Its runs' times are then the whole budget, not a first solution.
    pub fn is_anytime(self) -> bool {
        self == PlannerKind::Sst
    }

    /// Does it choose each control as the best of `k` sampled toward a target (OMPL's
    /// directed control sampler, which only RRT asks for)? The others ignore `k`.
    pub fn takes_best_of_k(self) -> bool {
        matches!(self, PlannerKind::PcRrt | PlannerKind::StaticRrt)
    }

    /// Does it treat every object but the goal object as a static obstacle (Static RRT)?
    pub fn pins_clutter(self) -> bool {
        self == PlannerKind::StaticRrt
    }

    /// Are its solutions control paths (a plan file holds controls)? DARRT's are
    /// sequences of primitives.
    pub fn yields_controls(self) -> bool {
        !matches!(self, PlannerKind::Darrt | PlannerKind::DarrtPickPlace)
    }

    /// Propagation steps the first attempt of a search may take before it starts over
    /// (`Restarting` in `cpp/search/restarts.h`; later attempts get Luby multiples of it), or 0:
    /// never. Push KPIECE restarts; the paper's planners and OMPL's run as published.
    pub fn restart_steps(self) -> u64 {
        match self {
            PlannerKind::PushKpiece => PUSH_KPIECE_RESTART_STEPS,
            _ => 0,
        }
    }

    /// Propagation steps after which a search none of whose states has moved the goal
    /// object hands over to PC RRT (`Fallback` in `cpp/search/fallback.h`), or 0:
    /// never. Only Push KPIECE falls back: its guided pushes need the hand at the goal
    /// object first, and where the arm cannot get there they build nothing.
    pub fn fallback_steps(self) -> u64 {
        match self {
            PlannerKind::PushKpiece => PUSH_KPIECE_FALLBACK_STEPS,
            _ => 0,
        }
    }

    /// Refuses `steps` > 0 of patience for a planner that does not fall back; `name` is the
    /// setting's (`--fallback`, `fallback_steps`).
    pub fn check_fallback(self, steps: u64, name: &str) -> Result<(), String> {
        match steps > 0 && self.fallback_steps() == 0 {
            true => Err(format!(
                "{name} {steps}: only {} falls back (to {}), not {}",
                PlannerKind::PushKpiece.name(),
                PlannerKind::PcRrt.name(),
                self.name()
            )),
            false => Ok(()),
        }
    }

    /// Whether the threads of a plan share one search, its propagations running in
    /// parallel (`ParallelKPIECE`, `cpp/search/parallel_kpiece.h`), rather than each running a
    /// search of its own (`Portfolio`, `cpp/search/portfolio.h`).
    pub fn shares_one_search(self) -> bool {
        matches!(self, PlannerKind::Kpiece | PlannerKind::PushKpiece)
    }

    /// Whether the model refuses propagations past the time limit while this planner
    /// searches, so that an extension of k long controls ends on time (OMPL checks the
    /// limit only between extensions). Not PDST's: it propagates its motions again, to
    /// split them at cell borders and to return its path, and a propagation refused
    /// there would put wrong states in its tree. It stops instead once the time left is
    /// shorter than its longest iteration so far (`cpp/search/portfolio.h`).
    pub fn cut_at_time_limit(self) -> bool {
        !matches!(self, PlannerKind::Pdst)
    }
}

impl FromStr for PlannerKind {
    type Err = String;

    fn from_str(name: &str) -> Result<Self, String> {
        crate::input::by_name(&PlannerKind::ALL, PlannerKind::name, "planner", name)
    }
}

impl fmt::Display for PlannerKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// In files (plan files, logs) a planner is its name.
impl serde::Serialize for PlannerKind {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.serialize_str(self.name())
    }
}

impl<'de> serde::Deserialize<'de> for PlannerKind {
    fn deserialize<D: serde::Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        let name = String::deserialize(deserializer)?;
        name.parse().map_err(serde::de::Error::custom)
    }
}
