//! Choosing designs: the best by one objective, and the Pareto front of rectangle area against
//! GCI.

use std::str::FromStr;

use crate::{DesignStatus, Evaluation};

/// What `--best` maximises.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Objective {
    /// The largest rectangle's area.
    #[default]
    Rectangle,
    /// The GCI over the largest rectangle.
    Gci,
    /// The reachable area.
    Area,
    /// The worst LCI over the largest rectangle.
    LciMin,
    /// The total time of the timed programs, minimised.
    Time,
    /// The Adept cycle's time, minimised.
    Cycle,
}

impl Objective {
    /// Every objective, as `--objective` spells it.
    pub const NAMES: [&'static str; 6] = ["rect", "gci", "area", "lci-min", "time", "cycle"];

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

    /// The CSV column this objective reads (`rect` is `rect_w_mm × rect_h_mm`).
    pub fn name(self) -> &'static str {
        Objective::NAMES[self as usize]
    }
}

impl FromStr for Objective {
    type Err = String;

    fn from_str(text: &str) -> Result<Objective, String> {
        match text {
            "rect" => Ok(Objective::Rectangle),
            "gci" => Ok(Objective::Gci),
            "area" => Ok(Objective::Area),
            "lci-min" => Ok(Objective::LciMin),
            "time" => Ok(Objective::Time),
            "cycle" => Ok(Objective::Cycle),
            _ => Err(format!("expected one of {}", Objective::NAMES.join(", "))),
        }
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

#[cfg(test)]
mod tests {
    use biscara_robot::Rectangle;

    use super::*;
    use crate::Design;

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
}
