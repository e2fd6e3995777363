//! A whole sweep as one request, and what its outcome writes: the Pareto front's rows, the
//! best design's robot, the atlas picture.

use std::io::{BufRead, Write};

use biscara_kinematics::Robot;
use biscara_view::{Atlas, AtlasCell, ImageFormat, ViewError, draw_atlas};

use crate::{
    Collector, Columns, DesignError, DesignGrid, Evaluator, Objective, ParamRange, ProgramTimer,
    RowReader, Shard, Sweep, SweepOutcome, Task, header, write_row,
};

/// A design sweep as `biscara design` asks for it: the ranges, the measure and what is chosen.
#[derive(Debug, Clone)]
pub struct SweepRequest {
    /// Proximal link lengths, mm.
    pub l1: ParamRange,
    /// Distal link lengths, mm.
    pub l2: ParamRange,
    /// Distances between the base joints, mm.
    pub base: ParamRange,
    /// The workspace grid step, mm.
    pub step: f64,
    /// A task rectangle every chosen design must cover.
    pub task: Option<Task>,
    /// What the best design maximises.
    pub objective: Objective,
    /// Programs timed on every design, `(name, text)` (none: no time column).
    pub programs: Vec<(String, String)>,
    /// Centre each program in each design's rectangle first.
    pub fit: bool,
    /// The part of the sweep evaluated.
    pub shard: Shard,
}

impl SweepRequest {
    /// The sweep of designs derived from `robot`; an error for an impossible grid or step, or
    /// for the time objective without programs.
    pub fn sweep(self, robot: Robot) -> Result<Sweep, DesignError> {
        let grid = DesignGrid::new(self.l1, self.l2, self.base)?;
        let mut evaluator = Evaluator::new(robot, self.step, self.task)?;
        if !self.programs.is_empty() {
            evaluator = evaluator.with_programs(ProgramTimer::new(self.programs, self.fit));
        } else if self.objective == Objective::Time {
            return Err(DesignError::NoPrograms);
        }
        if self.objective == Objective::Cycle {
            evaluator = evaluator.with_cycle();
        }
        Ok(Sweep::new(evaluator, grid, self.shard))
    }
}

impl SweepOutcome {
    /// Reads a design CSV (a sweep's, or merged) and collects what a sweep over its rows finds,
    /// every design's atlas value included.
    pub fn read(input: impl BufRead, objective: Objective) -> Result<SweepOutcome, DesignError> {
        let mut collector = Collector::new(objective, true);
        for row in RowReader::new(input)? {
            collector.consider(&row?);
        }
        Ok(collector.finish())
    }

    /// Writes the Pareto front as a design CSV with `columns`.
    pub fn write_pareto(&self, out: &mut dyn Write, columns: Columns) -> std::io::Result<()> {
        writeln!(out, "{}", header(columns))?;
        for evaluation in &self.pareto {
            write_row(out, columns, evaluation)?;
        }
        Ok(())
    }

    /// The robot of the best design (`sweep`'s robot with its links and base), or an error
    /// that says which conditions no design met (`task`: a task rectangle was given).
    pub fn best_robot(&self, sweep: &Sweep, task: bool) -> Result<Robot, DesignError> {
        match &self.best {
            Some(best) => Ok(sweep.evaluator().robot_of(&best.design)),
            None => Err(DesignError::NoneChosen { task, objective: self.objective }),
        }
    }

    /// Draws the atlas of the cells (the objective's index over l1 × l2, a panel per base),
    /// the best design ringed, as SVG or PNG bytes.
    pub fn draw_atlas(&self, format: ImageFormat) -> Result<Vec<u8>, ViewError> {
        let cells: Vec<AtlasCell> = self
            .cells
            .iter()
            .map(|c| AtlasCell {
                l1: c.design.l1,
                l2: c.design.l2,
                base: c.design.base,
                value: c.value,
            })
            .collect();
        let index = self.objective.description();
        let title = format!("Design atlas: {index} over l1 × l2, per base distance");
        let chosen = self.best.map(|e| [e.design.l1, e.design.l2, e.design.base]);
        draw_atlas(&Atlas { title: &title, index, cells: &cells, chosen }, format)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn request(objective: Objective, programs: Vec<(String, String)>) -> SweepRequest {
        SweepRequest {
            l1: ParamRange::parse("l1", "200:220:2").expect("a range"),
            l2: ParamRange::parse("l2", "250:250:1").expect("a range"),
            base: ParamRange::parse("base", "150:150:1").expect("a range"),
            step: 10.0,
            task: None,
            objective,
            programs,
            fit: false,
            shard: "1/1".parse().expect("a shard"),
        }
    }

    #[test]
    fn a_sweep_request_checks_its_objective_and_sets_the_columns() {
        let err = request(Objective::Time, Vec::new()).sweep(Robot::default());
        assert!(matches!(err, Err(DesignError::NoPrograms)));
        let sweep = request(Objective::Cycle, Vec::new()).sweep(Robot::default()).expect("ok");
        assert_eq!(sweep.count(), 2);
        assert_eq!(sweep.evaluator().columns(), Columns { task: false, time: false, cycle: true });
        let programs = vec![("a.ngc".to_owned(), "G0 X0\n".to_owned())];
        let sweep = request(Objective::Rectangle, programs).sweep(Robot::default()).expect("ok");
        assert_eq!(sweep.evaluator().columns(), Columns { task: false, time: true, cycle: false });
    }

    #[test]
    fn an_outcome_read_back_writes_its_front_and_names_its_best_robot() {
        let sweep = request(Objective::Rectangle, Vec::new()).sweep(Robot::default()).expect("ok");
        let columns = sweep.evaluator().columns();
        let mut csv = format!("{}\n", header(columns)).into_bytes();
        let options =
            crate::SweepOptions { threads: 1, objective: Objective::Rectangle, cells: true };
        let outcome = sweep
            .run(&options, |e| write_row(&mut csv, columns, e).map_err(DesignError::from))
            .expect("the sweep runs");
        let read = SweepOutcome::read(&csv[..], Objective::Rectangle).expect("read back");
        assert_eq!(read.count, 2);
        assert_eq!(read.cells.len(), 2);
        let mut front = Vec::new();
        outcome.write_pareto(&mut front, columns).expect("written");
        let front = String::from_utf8(front).expect("UTF-8");
        assert_eq!(front.lines().count(), 1 + outcome.pareto.len());
        let best = outcome.best.expect("a best design");
        let robot = outcome.best_robot(&sweep, false).expect("a robot");
        assert_eq!((robot.links.l1, robot.links.l2), (best.design.l1, best.design.l2));
        let none = SweepOutcome { best: None, ..outcome };
        let err = none.best_robot(&sweep, true).expect_err("none chosen").to_string();
        assert_eq!(err, "no design has a rectangle and covers the task");
        let bytes = none.draw_atlas(ImageFormat::Svg).expect("drawn");
        assert!(String::from_utf8_lossy(&bytes).contains("Design atlas: "));
    }
}
