//! Choosing designs: the best by one objective, and the Pareto front of rectangle area against
//! GCI.

use std::str::FromStr;

use crate::{Design, DesignStatus, Evaluation};

/// What `--best` maximises.
///
/// The first paragraph of each variant's documentation is the help of `--objective`'s and
/// `--index`'s values (the `clap` feature).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[cfg_attr(feature = "clap", derive(clap::ValueEnum))]
pub enum Objective {
    /// The largest rectangle's area, mm².
    #[default]
    #[cfg_attr(feature = "clap", value(name = "rect"))]
    Rectangle,
    /// The GCI over the largest rectangle.
    Gci,
    /// The reachable area, mm².
    Area,
    /// The worst LCI over the largest rectangle.
    LciMin,
    /// The total time of --programs, s (shortest best).
    ///
    /// The timed programs' total time, minimised.
    Time,
    /// The Adept cycle's time (`biscara cycle`), s (shortest best).
    Cycle,
}

impl Objective {
    /// Every objective.
    pub const ALL: [Objective; 6] = [
        Objective::Rectangle,
        Objective::Gci,
        Objective::Area,
        Objective::LciMin,
        Objective::Time,
        Objective::Cycle,
    ];

    /// The index this objective reads for `evaluation` (the time for [`Objective::Time`]);
    /// `None` when the design has none (no timed run).
    pub fn value(self, evaluation: &Evaluation) -> Option<f64> {
        match self {
            Objective::Rectangle => Some(evaluation.rectangle_area()),
            Objective::Gci => Some(evaluation.gci),
            Objective::Area => Some(evaluation.area_mm2),
            Objective::LciMin => Some(evaluation.lci_min),
            Objective::Time => evaluation.time_s,
            Objective::Cycle => evaluation.cycle_s,
        }
    }

    /// The value maximised: [`Objective::value`], negated for the time.
    fn score(self, evaluation: &Evaluation) -> Option<f64> {
        let value = self.value(evaluation)?;
        Some(if matches!(self, Objective::Time | Objective::Cycle) { -value } else { value })
    }

    /// The objective as `--objective` spells it. The CSV columns it reads: `rect_w_mm ×
    /// rect_h_mm` (rect), `gci`, `area_mm2` (area), `lci_min` (lci-min), `time_s` (time),
    /// `cycle_s` (cycle).
    pub fn name(self) -> &'static str {
        match self {
            Objective::Rectangle => "rect",
            Objective::Gci => "gci",
            Objective::Area => "area",
            Objective::LciMin => "lci-min",
            Objective::Time => "time",
            Objective::Cycle => "cycle",
        }
    }

    /// What the objective's index is, with its unit, as a picture's legend says it.
    pub fn description(self) -> &'static str {
        match self {
            Objective::Rectangle => "largest rectangle, mm²",
            Objective::Gci => "GCI",
            Objective::Area => "reachable area, mm²",
            Objective::LciMin => "worst LCI",
            Objective::Time => "time of the programs, s",
            Objective::Cycle => "Adept cycle time, s",
        }
    }
}

impl FromStr for Objective {
    type Err = String;

    fn from_str(text: &str) -> Result<Objective, String> {
        Objective::ALL.into_iter().find(|objective| objective.name() == text).ok_or_else(|| {
            let names: Vec<&str> = Objective::ALL.iter().map(|o| o.name()).collect();
            format!("expected one of {}", names.join(", "))
        })
    }
}

/// Whether a design may be chosen: evaluated with a rectangle, and covering the task if any.
pub fn eligible(evaluation: &Evaluation) -> bool {
    evaluation.status == DesignStatus::Ok && evaluation.task_ok != Some(false)
}

/// The best eligible design seen so far by one objective (the largest value, the shortest time);
/// ties go to the first seen (in a sweep, the lowest index).
#[derive(Debug, Clone)]
pub struct Best {
    objective: Objective,
    best: Option<Evaluation>,
}

impl Best {
    /// No design yet.
    pub fn new(objective: Objective) -> Best {
        Best { objective, best: None }
    }

    /// Takes `evaluation` when it is eligible and better than the best so far.
    pub fn consider(&mut self, evaluation: &Evaluation) {
        if !eligible(evaluation) {
            return;
        }
        let Some(score) = self.objective.score(evaluation) else { return };
        let better = |best: Evaluation| self.objective.score(&best).is_none_or(|b| score > b);
        if self.best.is_none_or(better) {
            self.best = Some(*evaluation);
        }
    }

    /// The best design, if any was eligible.
    pub fn get(&self) -> Option<&Evaluation> {
        self.best.as_ref()
    }
}

/// The eligible designs that no other beats in both rectangle area and GCI (at least as good in
/// both, better in one). Kept as the sweep runs: memory grows with the front, not the sweep.
#[derive(Debug, Clone, Default)]
pub struct ParetoFront {
    front: Vec<Evaluation>,
}

impl ParetoFront {
    /// An empty front.
    pub fn new() -> ParetoFront {
        ParetoFront::default()
    }

    /// Adds `evaluation` when eligible and not dominated, dropping what it dominates. Of two
    /// designs with equal values the first stays.
    pub fn consider(&mut self, evaluation: &Evaluation) {
        if !eligible(evaluation) {
            return;
        }
        let key = |e: &Evaluation| (e.rectangle_area(), e.gci);
        let (area, gci) = key(evaluation);
        if self.front.iter().any(|e| {
            let (a, g) = key(e);
            a >= area && g >= gci
        }) {
            return;
        }
        self.front.retain(|e| {
            let (a, g) = key(e);
            !(area >= a && gci >= g)
        });
        self.front.push(*evaluation);
    }

    /// The front, by rectangle area, largest first (GCI then rises).
    pub fn designs(&self) -> Vec<Evaluation> {
        let mut front = self.front.clone();
        front.sort_by(|a, b| b.rectangle_area().total_cmp(&a.rectangle_area()));
        front
    }
}

/// One cell of a design atlas: a design and its objective's index (`None` when the design may
/// not be chosen or has no such index).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AtlasValue {
    /// The design.
    pub design: Design,
    /// The objective's index ([`Objective::value`]) of an [`eligible`] design.
    pub value: Option<f64>,
}

/// What a sweep (or a design CSV read back) keeps as its rows go by: the best design, the
/// Pareto front and, when asked, every design's atlas value.
#[derive(Debug, Clone)]
pub struct Collector {
    best: Best,
    pareto: ParetoFront,
    /// The atlas values, kept when asked for (memory grows with the designs then).
    cells: Option<Vec<AtlasValue>>,
    count: u64,
    cycle_failures: u64,
}

/// What a sweep found ([`Collector::finish`], [`crate::Sweep::run`]); its `Display` is the
/// one-line summary `design` notes.
#[derive(Debug, Clone, PartialEq)]
pub struct SweepOutcome {
    /// How many designs were evaluated (read).
    pub count: u64,
    /// What the best design maximises.
    pub objective: Objective,
    /// The best eligible design by the objective.
    pub best: Option<Evaluation>,
    /// The Pareto front ([`ParetoFront::designs`]).
    pub pareto: Vec<Evaluation>,
    /// Every design's atlas value in order, when asked for (else empty).
    pub cells: Vec<AtlasValue>,
    /// How many `ok` designs the Adept cycle could not run on (`--objective cycle`: their
    /// `cycle_s` is empty).
    pub cycle_failures: u64,
    /// The first of them and why the cycle could not run on it (known to a sweep; `None` for a
    /// CSV read back, whose rows do not say why).
    pub first_cycle_failure: Option<(Design, String)>,
}

impl Collector {
    /// Nothing seen yet; `cells`: keep every design's value for an atlas.
    pub fn new(objective: Objective, cells: bool) -> Collector {
        Collector {
            best: Best::new(objective),
            pareto: ParetoFront::new(),
            cells: cells.then(Vec::new),
            count: 0,
            cycle_failures: 0,
        }
    }

    /// Takes one design's evaluation.
    pub fn consider(&mut self, evaluation: &Evaluation) {
        self.count += 1;
        if cycle_failed(self.best.objective, evaluation) {
            self.cycle_failures += 1;
        }
        self.best.consider(evaluation);
        self.pareto.consider(evaluation);
        if let Some(cells) = &mut self.cells {
            let value =
                if eligible(evaluation) { self.best.objective.value(evaluation) } else { None };
            cells.push(AtlasValue { design: evaluation.design, value });
        }
    }

    /// What was found.
    pub fn finish(self) -> SweepOutcome {
        SweepOutcome {
            count: self.count,
            objective: self.best.objective,
            best: self.best.get().copied(),
            pareto: self.pareto.designs(),
            cells: self.cells.unwrap_or_default(),
            cycle_failures: self.cycle_failures,
            first_cycle_failure: None,
        }
    }
}

/// Whether the Adept cycle, timed for the `cycle` objective, could not run on an `ok` design.
pub(crate) fn cycle_failed(objective: Objective, evaluation: &Evaluation) -> bool {
    objective == Objective::Cycle
        && evaluation.status == DesignStatus::Ok
        && evaluation.cycle_s.is_none()
}

/// `n` designs: "1 design", "3 designs".
fn designs(n: impl Into<u64>) -> String {
    let n = n.into();
    format!("{n} design{}", if n == 1 { "" } else { "s" })
}

impl std::fmt::Display for SweepOutcome {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let count = designs(self.count);
        let Some(best) = self.best else {
            if self.cycle_failures == 0 {
                return write!(f, "{count} evaluated; none has a rectangle");
            }
            write!(f, "{count} evaluated; none has a cycle time")?;
            return self.write_cycle_failures(f);
        };
        let d = best.design;
        let (w, h) = best.rectangle.map_or((0.0, 0.0), |r| (r.width(), r.height()));
        write!(
            f,
            "{count} evaluated; best by {}: l1 = {} mm, l2 = {} mm, base = {} mm \
             (rectangle {w:.0} × {h:.0} mm, GCI {:.3}, worst LCI {:.3}",
            self.objective.name(),
            d.l1,
            d.l2,
            d.base,
            best.gci,
            best.lci_min,
        )?;
        if let Some(time) = best.time_s {
            write!(f, ", programs {time:.3} s")?;
        }
        if let Some(cycle) = best.cycle_s {
            write!(f, ", Adept cycle {cycle:.3} s")?;
        }
        write!(
            f,
            "); Pareto front of rectangle area and GCI: {}",
            designs(self.pareto.len() as u64)
        )?;
        self.write_cycle_failures(f)
    }
}

impl SweepOutcome {
    /// `; the Adept cycle could not run on N designs (first: …)`, when it could not.
    fn write_cycle_failures(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        if self.cycle_failures == 0 {
            return Ok(());
        }
        write!(f, "; the Adept cycle could not run on {}", designs(self.cycle_failures))?;
        match &self.first_cycle_failure {
            Some((d, reason)) => write!(
                f,
                " (first, design {}: l1 = {} mm, l2 = {} mm, base = {} mm: {reason})",
                d.index, d.l1, d.l2, d.base
            ),
            None => write!(f, " (their cycle_s is empty)"),
        }
    }
}

#[cfg(test)]
mod tests {
    use biscara_robot::Rectangle;

    use super::*;

    fn design(index: u64, side: f64, gci: f64) -> Evaluation {
        Evaluation {
            design: Design { index, l1: 1.0, l2: 1.0, base: 1.0 },
            status: DesignStatus::Ok,
            area_mm2: side * side * 2.0,
            rectangle: Some(Rectangle { min: [0.0, 0.0], max: [side, side] }),
            gci,
            lci_min: gci / 2.0,
            task_ok: None,
            time_s: Some(10.0 - side),
            cycle_s: Some(5.0 - 0.01 * side),
        }
    }

    #[test]
    fn the_best_is_the_first_maximum_of_eligible_designs() {
        let mut best = Best::new(Objective::Rectangle);
        let mut refused = design(0, 100.0, 0.9);
        refused.task_ok = Some(false);
        for evaluation in
            [refused, design(1, 10.0, 0.5), design(2, 20.0, 0.1), design(3, 20.0, 0.9)]
        {
            best.consider(&evaluation);
        }
        assert_eq!(best.get().map(|e| e.design.index), Some(2));
        let mut best = Best::new(Objective::Gci);
        best.consider(&design(4, 1.0, 0.3));
        best.consider(&design(5, 1.0, 0.7));
        assert_eq!(best.get().map(|e| e.design.index), Some(5));
        let mut best = Best::new(Objective::Time);
        let mut untimed = design(6, 9.5, 0.3);
        untimed.time_s = None;
        for evaluation in [design(7, 2.0, 0.3), untimed, design(8, 3.0, 0.3), design(9, 1.0, 0.3)] {
            best.consider(&evaluation);
        }
        assert_eq!(best.get().map(|e| e.design.index), Some(8), "the shortest time");
    }

    #[test]
    fn the_front_keeps_only_undominated_designs() {
        let mut front = ParetoFront::new();
        for evaluation in [
            design(0, 10.0, 0.5),
            design(1, 20.0, 0.4),
            design(2, 15.0, 0.3), // dominated by 1
            design(3, 5.0, 0.9),
            design(4, 10.0, 0.6), // dominates 0
        ] {
            front.consider(&evaluation);
        }
        let indices: Vec<u64> = front.designs().iter().map(|e| e.design.index).collect();
        assert_eq!(indices, [1, 4, 3]);
    }

    #[test]
    fn the_collector_keeps_the_best_the_front_and_each_designs_value() {
        let mut refused = design(1, 100.0, 0.95);
        refused.task_ok = Some(false);
        let mut collector = Collector::new(Objective::Gci, true);
        for evaluation in [design(0, 10.0, 0.5), refused, design(2, 20.0, 0.4)] {
            collector.consider(&evaluation);
        }
        let outcome = collector.finish();
        assert_eq!(outcome.count, 3);
        assert_eq!(outcome.best.map(|e| e.design.index), Some(0), "the largest GCI allowed");
        let front: Vec<u64> = outcome.pareto.iter().map(|e| e.design.index).collect();
        assert_eq!(front, [2, 0]);
        let values: Vec<Option<f64>> = outcome.cells.iter().map(|c| c.value).collect();
        assert_eq!(values, [Some(0.5), None, Some(0.4)], "a refused design has no value");
        assert_eq!(
            outcome.to_string(),
            "3 designs evaluated; best by gci: l1 = 1 mm, l2 = 1 mm, base = 1 mm (rectangle \
             10 × 10 mm, GCI 0.500, worst LCI 0.250, programs 0.000 s, Adept cycle 4.900 s); \
             Pareto front of rectangle area and GCI: 2 designs"
        );
        let without = Collector::new(Objective::Gci, false);
        let outcome = without.finish();
        assert!(outcome.cells.is_empty());
        assert_eq!(outcome.to_string(), "0 designs evaluated; none has a rectangle");
        // One is one design, not "1 designs".
        let mut single = Collector::new(Objective::Rectangle, false);
        single.consider(&design(0, 10.0, 0.5));
        let text = single.finish().to_string();
        assert!(text.starts_with("1 design evaluated; best by rect"), "{text}");
        assert!(text.ends_with("Pareto front of rectangle area and GCI: 1 design"), "{text}");
    }

    #[test]
    fn objectives_are_named_as_the_command_line_spells_them() {
        for objective in Objective::ALL {
            assert_eq!(objective.name().parse::<Objective>(), Ok(objective));
        }
        assert_eq!(Objective::LciMin.name(), "lci-min");
        assert!(
            "best".parse::<Objective>().unwrap_err().contains("rect, gci, area, lci-min, time")
        );
    }
}
