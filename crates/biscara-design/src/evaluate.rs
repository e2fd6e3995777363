//! One design evaluated: its workspace as `biscara workspace` computes it, the largest
//! rectangle, and the conditioning of the Jacobian over that rectangle.

use biscara_kinematics::{Chain, Kinematics, PlanarConfiguration, Robot, RobotModel};
use biscara_robot::{CycleConfig, Rectangle, Workspace, adept_cycle};

use crate::{Columns, Design, DesignError, ProgramTimer, Task};

/// Whether a design could be evaluated.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DesignStatus {
    /// Evaluated, with a rectangle.
    Ok,
    /// A valid robot, but no 2 × 2 block of grid points is reachable: no rectangle.
    Empty,
    /// Not a robot: its home pose does not assemble (the base wider than 2·l2) or the robot file
    /// rejects it.
    Invalid,
}

impl DesignStatus {
    /// The word in the CSV's `status` column.
    pub fn as_str(self) -> &'static str {
        match self {
            DesignStatus::Ok => "ok",
            DesignStatus::Empty => "empty",
            DesignStatus::Invalid => "invalid",
        }
    }

    /// The status of a `status` column's word.
    pub fn parse(word: &str) -> Option<DesignStatus> {
        match word {
            "ok" => Some(DesignStatus::Ok),
            "empty" => Some(DesignStatus::Empty),
            "invalid" => Some(DesignStatus::Invalid),
            _ => None,
        }
    }
}

/// The indices of one design.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Evaluation {
    /// The design.
    pub design: Design,
    /// Whether it could be evaluated.
    pub status: DesignStatus,
    /// The reachable area, mm² (each reachable grid point one step × step cell; 0 unless ok or
    /// empty).
    pub area_mm2: f64,
    /// The largest axis-aligned rectangle of reachable grid points (`None` unless ok).
    pub rectangle: Option<Rectangle>,
    /// The mean of LCI = 1/cond(J) over the rectangle's grid points (0 without a rectangle).
    pub gci: f64,
    /// The smallest LCI over the rectangle's grid points (0 without a rectangle).
    pub lci_min: f64,
    /// Whether every grid point of the task rectangle is reachable (`None` without a task).
    pub task_ok: Option<bool>,
    /// The total time of the programs on this design, s (`None` without programs, for a design
    /// that is not ok, or when a program cannot run on it).
    pub time_s: Option<f64>,
    /// The Adept cycle's time on this design, s (`biscara cycle` at the centre of its
    /// rectangle; `None` unless asked for, for a design that is not ok, or where the cycle
    /// cannot run).
    pub cycle_s: Option<f64>,
}

impl Evaluation {
    /// The rectangle's area, mm² (0 without one).
    pub fn rectangle_area(&self) -> f64 {
        self.rectangle.map_or(0.0, |r| r.width() * r.height())
    }
}

/// Evaluates designs that differ from one robot file in l1, l2 and the base joints only.
#[derive(Debug, Clone)]
pub struct Evaluator {
    robot: Robot,
    step: f64,
    task: Option<Task>,
    timer: Option<ProgramTimer>,
    cycle: bool,
}

impl Evaluator {
    /// Designs on `robot` (everything but l1, l2 and the base taken from it), workspaces on a
    /// grid of `step` mm, and a task rectangle to cover when given.
    pub fn new(robot: Robot, step: f64, task: Option<Task>) -> Result<Evaluator, DesignError> {
        Workspace::check_step(step)?;
        Ok(Evaluator { robot, step, task, timer: None, cycle: false })
    }

    /// Also times `timer`'s programs on every design that is ok.
    pub fn with_programs(mut self, timer: ProgramTimer) -> Evaluator {
        self.timer = Some(timer);
        self
    }

    /// Also times the Adept cycle (`biscara cycle`, with its defaults, at the centre of the
    /// design's rectangle) on every design that is ok: the robot file's motors and payload, its
    /// bodies scaled with the links where its `dynamics` does not give them.
    pub fn with_cycle(mut self) -> Evaluator {
        self.cycle = true;
        self
    }

    /// Which columns this evaluator's rows have.
    pub fn columns(&self) -> Columns {
        Columns { task: self.task.is_some(), time: self.timer.is_some(), cycle: self.cycle }
    }

    /// The grid step, mm.
    pub fn step(&self) -> f64 {
        self.step
    }

    /// The task rectangle, if any.
    pub fn task(&self) -> Option<Task> {
        self.task
    }

    /// The robot file of `design`: the base robot with its links and base joints (at ±base/2).
    pub fn robot_of(&self, design: &Design) -> Robot {
        let mut robot = self.robot.clone();
        robot.links.l1 = design.l1;
        robot.links.l2 = design.l2;
        robot.base.b1x = 0.5 * design.base;
        robot.base.b2x = -0.5 * design.base;
        robot
    }

    /// Evaluates `design`.
    pub fn evaluate(&self, design: Design) -> Evaluation {
        let mut evaluation = Evaluation {
            design,
            status: DesignStatus::Invalid,
            area_mm2: 0.0,
            rectangle: None,
            gci: 0.0,
            lci_min: 0.0,
            task_ok: self.task.map(|_| false),
            time_s: None,
            cycle_s: None,
        };
        let Ok(model) = Kinematics::new(&self.robot_of(&design)) else {
            return evaluation;
        };
        let Ok(workspace) = Workspace::compute(&model, self.step) else {
            return evaluation;
        };
        evaluation.area_mm2 = workspace.area_mm2();
        evaluation.task_ok = self.task.map(|task| covers(&workspace, &task));
        let Ok(rectangle) = workspace.largest_rectangle() else {
            evaluation.status = DesignStatus::Empty;
            return evaluation;
        };
        let (gci, lci_min) = conditioning(&model, &workspace, &rectangle);
        let time_s = self.timer.as_ref().and_then(|timer| timer.time(&self.robot_of(&design)));
        let cycle_s = self.cycle.then(|| self.cycle_time(&design, rectangle.center())).flatten();
        Evaluation {
            time_s,
            cycle_s,
            status: DesignStatus::Ok,
            rectangle: Some(rectangle),
            gci,
            lci_min,
            ..evaluation
        }
    }
}

impl Evaluator {
    /// The Adept cycle's time on `design` centred at `at`; `None` where it cannot run.
    fn cycle_time(&self, design: &Design, at: [f64; 2]) -> Option<f64> {
        self.run_cycle(design, at).ok()
    }

    /// The Adept cycle's time on `design` centred at `at`, or why it cannot run.
    fn run_cycle(&self, design: &Design, at: [f64; 2]) -> Result<f64, String> {
        let model = RobotModel::new(self.robot_of(design)).map_err(|err| err.to_string())?;
        let config = CycleConfig { at: Some(at), ..CycleConfig::default() };
        adept_cycle(&model, &config).map(|report| report.cycle_s).map_err(|err| err.to_string())
    }

    /// Why the Adept cycle could not run on the `ok` design `evaluation` left without a
    /// `cycle_s` (`None` when it has one, is not `ok`, or the cycle was not asked for): the
    /// cycle run again, for the message only.
    pub fn cycle_failure(&self, evaluation: &Evaluation) -> Option<String> {
        if !self.cycle || evaluation.cycle_s.is_some() {
            return None;
        }
        let rectangle = evaluation.rectangle?;
        self.run_cycle(&evaluation.design, rectangle.center()).err()
    }
}

/// Whether every grid point of `workspace` inside `task` (edges included) is reachable; points
/// off the workspace's grid are not.
pub fn covers(workspace: &Workspace, task: &Task) -> bool {
    let step = workspace.step();
    let first = |v: f64| (v / step).ceil() as i64;
    let last = |v: f64| (v / step).floor() as i64;
    (first(task.min[1])..=last(task.max[1])).all(|j| {
        (first(task.min[0])..=last(task.max[0])).all(|i| {
            let (x, y) = (i as f64 * step, j as f64 * step);
            workspace.index_of(x, y).is_some_and(|(i, j)| workspace.is_reachable(i, j))
        })
    })
}

/// The mean and the smallest LCI over the grid points of `rectangle` (all reachable).
pub fn conditioning(
    model: &Kinematics,
    workspace: &Workspace,
    rectangle: &Rectangle,
) -> (f64, f64) {
    let (Some((i0, j0)), Some((i1, j1))) = (
        workspace.index_of(rectangle.min[0], rectangle.min[1]),
        workspace.index_of(rectangle.max[0], rectangle.max[1]),
    ) else {
        return (0.0, 0.0);
    };
    let (mut sum, mut min, mut count) = (0.0, f64::INFINITY, 0u64);
    for j in j0..=j1 {
        for i in i0..=i1 {
            let [x, y] = workspace.point(i, j);
            let lci = model.configuration(x, y).map_or(0.0, |c| lci(&c));
            sum += lci;
            min = min.min(lci);
            count += 1;
        }
    }
    if count == 0 { (0.0, 0.0) } else { (sum / count as f64, min) }
}

/// The local conditioning index 1/cond(J) of the planar Jacobian `J = ∂(x, y)/∂(θ1, θ2)` at
/// `configuration`: 1 where J is isotropic, 0 at a singularity of either type.
///
/// `J = A⁻¹·B` with `A` the rows `z_i = P − E_i` and `B = diag((E_i − b_i) × z_i)`. The factor
/// 1/det A scales both singular values alike, so cond(J) = cond(M) with the columns
/// `c1 = B1·(z2y, −z2x)`, `c2 = B2·(−z1y, z1x)`; for a 2 × 2 matrix with p = |c1|², q = |c2|²,
/// r = c1·c2 and d = |det M|, σmin/σmax = 2d / (p + q + √((p − q)² + 4r²)).
pub fn lci(configuration: &PlanarConfiguration) -> f64 {
    let z1 = configuration.distal(Chain::One);
    let z2 = configuration.distal(Chain::Two);
    let b1 = configuration.proximal(Chain::One).perp(&z1);
    let b2 = configuration.proximal(Chain::Two).perp(&z2);
    let p = b1 * b1 * z2.norm_squared();
    let q = b2 * b2 * z1.norm_squared();
    let r = -b1 * b2 * z1.dot(&z2);
    let d = (b1 * b2 * z1.perp(&z2)).abs();
    // √ rather than hypot: the magnitudes are far from overflow, and libm's hypot was 11 % of a
    // sweep.
    let spread = ((p - q) * (p - q) + 4.0 * r * r).sqrt();
    let denominator = p + q + spread;
    if denominator > 0.0 { 2.0 * d / denominator } else { 0.0 }
}

#[cfg(test)]
mod tests {
    use biscara_kinematics::{PlanarJacobian, Pose};

    use super::*;

    #[test]
    fn lci_is_the_inverse_condition_number_of_the_jacobian() {
        let model = Kinematics::default();
        let mut checked = 0;
        for i in 0..40 {
            for j in 0..40 {
                let pose =
                    Pose::new(-400.0 + 20.0 * f64::from(i), -50.0 + 14.0 * f64::from(j), 0.0, 0.0);
                let Ok(ik) = model.inverse(&pose) else { continue };
                let cond = PlanarJacobian::new(&ik.configuration).condition_number();
                let expected = if cond.is_finite() { 1.0 / cond } else { 0.0 };
                let found = lci(&ik.configuration);
                assert!((found - expected).abs() < 1e-9, "{pose:?}: {found} vs {expected}");
                assert!((0.0..=1.0).contains(&found));
                checked += 1;
            }
        }
        assert!(checked > 500);
    }

    #[test]
    fn a_base_wider_than_two_distal_links_is_invalid() {
        let evaluator = Evaluator::new(Robot::default(), 10.0, None).unwrap();
        let design = Design { index: 0, l1: 100.0, l2: 100.0, base: 250.0 };
        let evaluation = evaluator.evaluate(design);
        assert_eq!(evaluation.status, DesignStatus::Invalid);
        assert_eq!((evaluation.area_mm2, evaluation.gci), (0.0, 0.0));
    }

    #[test]
    fn the_step_is_checked() {
        assert!(Evaluator::new(Robot::default(), 0.0, None).is_err());
        assert!(Evaluator::new(Robot::default(), f64::NAN, None).is_err());
    }
}
