//! The sweep: every design of a grid (or of one shard of it) evaluated on worker threads and
//! handed back in index order, a block at a time.

use rayon::prelude::*;

use crate::{
    Collector, DesignError, DesignGrid, Evaluation, Evaluator, Objective, Shard, SweepOutcome,
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
            }
        }
        Ok(collector.finish())
    }
}
