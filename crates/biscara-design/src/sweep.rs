//! The sweep: every design of a grid (or of one shard of it) evaluated on worker threads and
//! handed back in index order, a block at a time.

use std::io::Write;

use rayon::prelude::*;

use crate::select::cycle_failed;
use crate::{
    Collector, DesignError, DesignGrid, Evaluation, Evaluator, Objective, Shard, SweepOutcome,
    header, write_row,
};

/// How many designs each worker thread gets per block: the memory a sweep holds is one block
/// of evaluations, whatever the number of designs.
const BLOCK_PER_THREAD: usize = 16;

/// How a sweep runs and what it keeps.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct SweepOptions {
    /// Worker threads (0: one per core).
    pub threads: usize,
    /// What the best design maximises.
    pub objective: Objective,
    /// Keep every design's atlas value ([`SweepOutcome::cells`]).
    pub cells: bool,
}

/// A sweep over a grid of designs.
#[derive(Debug, Clone)]
pub struct Sweep {
    evaluator: Evaluator,
    grid: DesignGrid,
    shard: Shard,
}

impl Sweep {
    /// The designs of `grid` in `shard`, each evaluated by `evaluator`.
    pub fn new(evaluator: Evaluator, grid: DesignGrid, shard: Shard) -> Sweep {
        Sweep { evaluator, grid, shard }
    }

    /// How many designs this sweep (its shard) evaluates.
    pub fn count(&self) -> u64 {
        self.shard.count(self.grid.len())
    }

    /// The evaluator.
    pub fn evaluator(&self) -> &Evaluator {
        &self.evaluator
    }

    /// Evaluates every design of the shard on `options.threads` worker threads and calls `each`
    /// with the evaluations in index order, as they are ready (to write the rows); stops at the
    /// first error `each` returns. Returns the best design, the Pareto front and, when asked,
    /// the atlas values.
    pub fn run<E: From<DesignError> + Send>(
        &self,
        options: &SweepOptions,
        mut each: impl FnMut(&Evaluation) -> Result<(), E>,
    ) -> Result<SweepOutcome, E> {
        let threads = options.threads;
        let mut collector = Collector::new(options.objective, options.cells);
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .map_err(|err| DesignError::Threads { threads, message: err.to_string() })?;
        let block = BLOCK_PER_THREAD * pool.current_num_threads().max(1);
        let mut indices = self.shard.indices(self.grid.len()).peekable();
        let mut designs = Vec::with_capacity(block);
        let mut evaluations = Vec::with_capacity(block);
        // Why the cycle could not run on the first design it failed on, for the summary.
        let mut first_cycle_failure = None;
        while indices.peek().is_some() {
            designs.clear();
            designs.extend(indices.by_ref().take(block).map(|index| self.grid.design(index)));
            pool.install(|| {
                designs
                    .par_iter()
                    .map(|design| self.evaluator.evaluate(*design))
                    .collect_into_vec(&mut evaluations);
            });
            for evaluation in &evaluations {
                each(evaluation)?;
                collector.consider(evaluation);
                if first_cycle_failure.is_none() && cycle_failed(options.objective, evaluation) {
                    first_cycle_failure = self
                        .evaluator
                        .cycle_failure(evaluation)
                        .map(|reason| (evaluation.design, reason));
                }
            }
        }
        Ok(SweepOutcome { first_cycle_failure, ..collector.finish() })
    }

    /// Runs the sweep as [`Sweep::run`] and writes its CSV to `out`: the header of the
    /// evaluator's columns, then each design's row as it is ready, calling `each` after every
    /// row (a progress bar).
    pub fn write_csv<E: From<DesignError> + From<std::io::Error> + Send>(
        &self,
        options: &SweepOptions,
        out: &mut dyn Write,
        mut each: impl FnMut(),
    ) -> Result<SweepOutcome, E> {
        let columns = self.evaluator.columns();
        writeln!(out, "{}", header(columns))?;
        self.run(options, |evaluation| -> Result<(), E> {
            write_row(out, columns, evaluation)?;
            each();
            Ok(())
        })
    }
}

#[cfg(test)]
mod tests {
    use biscara_kinematics::Robot;

    use super::*;
    use crate::{ParamRange, SweepRequest};

    #[test]
    fn the_csv_has_the_header_and_a_row_per_design() {
        let request = SweepRequest {
            l1: ParamRange::parse("l1", "200:220:2").unwrap(),
            l2: ParamRange::parse("l2", "300:300:1").unwrap(),
            base: ParamRange::parse("base", "150:150:1").unwrap(),
            step: 20.0,
            task: None,
            objective: Objective::Rectangle,
            programs: Vec::new(),
            fit: false,
            shard: "1/1".parse().unwrap(),
        };
        let sweep = request.sweep(Robot::default()).unwrap();
        let (mut out, mut rows) = (Vec::new(), 0);
        let options = SweepOptions { threads: 1, ..SweepOptions::default() };
        let outcome = sweep.write_csv::<DesignError>(&options, &mut out, || rows += 1).unwrap();
        let text = String::from_utf8(out).unwrap();
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!((lines.len(), rows), (3, 2));
        assert_eq!(lines[0], header(sweep.evaluator().columns()));
        assert!(lines[1].starts_with("0,200") && lines[2].starts_with("1,220"), "{text}");
        assert!(outcome.best.is_some());
    }

    #[test]
    fn a_design_the_cycle_cannot_run_on_is_counted_with_the_first_reason() {
        // l1 = 150, l2 = 200, base = 200: the rectangle is low (y < 0), where θ3 turning with
        // the distal link crosses ±180° during the cycle.
        let request = SweepRequest {
            l1: ParamRange::parse("l1", "150:150:1").unwrap(),
            l2: ParamRange::parse("l2", "200:200:1").unwrap(),
            base: ParamRange::parse("base", "200:200:1").unwrap(),
            step: 5.0,
            task: None,
            objective: Objective::Cycle,
            programs: Vec::new(),
            fit: false,
            shard: "1/1".parse().unwrap(),
        };
        let sweep = request.sweep(Robot::default()).unwrap();
        let options = SweepOptions { threads: 1, objective: Objective::Cycle, cells: false };
        let outcome = sweep.run::<DesignError>(&options, |_| Ok(())).unwrap();
        assert_eq!((outcome.best, outcome.cycle_failures), (None, 1));
        let (design, reason) = outcome.first_cycle_failure.clone().expect("a reason");
        assert_eq!(design.index, 0);
        assert!(reason.contains("the cycle"), "{reason}");
        let summary = outcome.to_string();
        assert!(
            summary.starts_with("1 design evaluated; none has a cycle time; the Adept cycle could \
                 not run on 1 design (first, design 0: l1 = 150 mm, l2 = 200 mm, base = 200 mm: the cycle"),
            "{summary}"
        );
    }
}
