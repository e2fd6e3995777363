//! From the points to the CL program: the paper's `trajectoryWorld` (docs/programming.md).

use std::collections::VecDeque;
use std::io::{BufRead, Write};

use biscara_cl::{Feed, FeedUnit, Goto, Statement, Units, write_statement};
use biscara_kinematics::{Kinematics, Pose};
use biscara_text::Located;

use crate::error::{PointsError, PointsErrorKind, WriteClError};
use crate::points::{Point, PointsReader, PointsStatement};

/// The name `biscara clf` gives the program (its PARTNO).
pub const PART_NAME: &str = "PICK AND PLACE";

/// The job's settings, with the points file's defaults (docs/programming.md).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct JobSettings {
    /// Start and end pose; default: the robot's home pose.
    pub home: Point,
    /// Height of the approach points above each pick and place, millimetres (default 50).
    pub approach_mm: f64,
    /// Feed of the approach and retract moves, millimetres per minute (default 3000).
    pub feed_mm_per_min: f64,
    /// Wait after each grip and release, seconds (default 0: no DELAY).
    pub dwell_s: f64,
}

impl JobSettings {
    /// The defaults for `model`: its home pose, 50 mm, 3000 mm/min, no dwell.
    pub fn defaults(model: &Kinematics) -> JobSettings {
        let [x, y, z, c] = model.home().to_degrees();
        JobSettings {
            home: Point { x, y, z, c },
            approach_mm: 50.0,
            feed_mm_per_min: 3000.0,
            dwell_s: 0.0,
        }
    }
}

/// The CL program of a points file, one [`Statement`] at a time (an iterator over the points
/// reader: a pair's statements are made when its place line is read, nothing else is kept).
///
/// Checks the order rules (settings before the first pick, each at most once; pick and place
/// alternate, starting with pick, at least one pair, ending with place) and that every pose and
/// the approach pose above it can be taken by the robot ([`Kinematics::inverse_checked`]: reach,
/// assembly mode, joint limits, singularity margin), and so does the home pose. Nothing is
/// yielded before the first pair has passed, so a file with no complete pair yields only its
/// error. After an error it yields nothing more.
///
/// The statements: `PARTNO`, `UNITS/MM`, a rapid to home; for each pair, a rapid above the pick,
/// the feed down (the first one preceded by `FEDRAT`), `PICK`, `DELAY` when dwelling, the feed
/// up, then the same for the place; finally a rapid home, `END`, `FINI`.
#[derive(Debug)]
pub struct ClProgram<'m, R> {
    reader: PointsReader<R>,
    model: &'m Kinematics,
    settings: JobSettings,
    /// Lines of `home`, `approach`, `feed`, `dwell` once seen.
    seen: [Option<usize>; 4],
    first_pick: Option<usize>,
    pending_pick: Option<(usize, Point)>,
    started: bool,
    feed_written: bool,
    queue: VecDeque<Statement>,
    done: bool,
}

impl<'m, R: BufRead> ClProgram<'m, R> {
    /// The program of the points file `input` for the robot `model`.
    pub fn new(input: R, model: &'m Kinematics) -> ClProgram<'m, R> {
        ClProgram {
            reader: PointsReader::new(input),
            model,
            settings: JobSettings::defaults(model),
            seen: [None; 4],
            first_pick: None,
            pending_pick: None,
            started: false,
            feed_written: false,
            queue: VecDeque::new(),
            done: false,
        }
    }

    /// The settings in force (final once the first pick has been read).
    pub fn settings(&self) -> &JobSettings {
        &self.settings
    }

    /// Reads points until there are statements to yield or the file ends.
    fn fill(&mut self) -> Result<(), PointsError> {
        while self.queue.is_empty() && !self.done {
            let Some(record) = self.reader.next() else {
                self.done = true;
                return self.end();
            };
            let record = record?;
            let line = record.line;
            match record.statement {
                PointsStatement::Home(point) => {
                    self.setting(line, 0, "home")?;
                    self.check(line, "home", point)?;
                    self.settings.home = point;
                }
                PointsStatement::Approach(value) => {
                    self.setting(line, 1, "approach")?;
                    self.settings.approach_mm = value;
                }
                PointsStatement::Feed(value) => {
                    self.setting(line, 2, "feed")?;
                    self.settings.feed_mm_per_min = value;
                }
                PointsStatement::Dwell(value) => {
                    self.setting(line, 3, "dwell")?;
                    self.settings.dwell_s = value;
                }
                PointsStatement::Pick(point) => {
                    if let Some((pick_line, _)) = self.pending_pick {
                        return Err(Located::at_line(
                            line,
                            PointsErrorKind::PickAfterPick { pick_line },
                        ));
                    }
                    if self.first_pick.is_none() {
                        self.first_pick = Some(line);
                        if self.seen[0].is_none() {
                            let home = self.settings.home;
                            self.check(line, "the robot's home pose (no `home` line)", home)?;
                        }
                    }
                    self.check(line, "pick", point)?;
                    let above = point.raised(self.settings.approach_mm);
                    self.check(line, "approach pose above the pick", above)?;
                    self.pending_pick = Some((line, point));
                }
                PointsStatement::Place(point) => {
                    let Some((_, pick)) = self.pending_pick.take() else {
                        return Err(Located::at_line(line, PointsErrorKind::PlaceBeforePick));
                    };
                    self.check(line, "place", point)?;
                    let above = point.raised(self.settings.approach_mm);
                    self.check(line, "approach pose above the place", above)?;
                    self.pair(pick, point);
                }
            }
        }
        Ok(())
    }

    fn setting(
        &mut self,
        line: usize,
        index: usize,
        keyword: &'static str,
    ) -> Result<(), PointsError> {
        if let Some(pick_line) = self.first_pick {
            return Err(Located::at_line(
                line,
                PointsErrorKind::SettingAfterPick { keyword, pick_line },
            ));
        }
        if let Some(first_line) = self.seen[index] {
            return Err(Located::at_line(line, PointsErrorKind::Duplicate { keyword, first_line }));
        }
        self.seen[index] = Some(line);
        Ok(())
    }

    fn check(&self, line: usize, what: &'static str, point: Point) -> Result<(), PointsError> {
        self.model
            .inverse_checked(&Pose::from_degrees(point.x, point.y, point.z, point.c))
            .map(|_| ())
            .map_err(|reason| {
                Located::at_line(
                    line,
                    PointsErrorKind::Unreachable { what, pose: point.to_array(), reason },
                )
            })
    }

    /// Queues the statements of one pick/place pair (and the header before the first).
    fn pair(&mut self, pick: Point, place: Point) {
        if !self.started {
            self.started = true;
            self.queue.push_back(Statement::PartNo(PART_NAME.to_owned()));
            self.queue.push_back(Statement::Units(Units::Millimetres));
            self.queue.push_back(Statement::Rapid);
            self.queue.push_back(goto(self.settings.home));
        }
        for (point, action) in [(pick, Statement::Pick), (place, Statement::Place)] {
            let above = point.raised(self.settings.approach_mm);
            self.queue.push_back(Statement::Rapid);
            self.queue.push_back(goto(above));
            if !self.feed_written {
                self.feed_written = true;
                self.queue.push_back(Statement::Feed(Feed {
                    value: self.settings.feed_mm_per_min,
                    unit: Some(FeedUnit::Mmpm),
                }));
            }
            self.queue.push_back(goto(point));
            self.queue.push_back(action);
            if self.settings.dwell_s > 0.0 {
                self.queue.push_back(Statement::Delay(self.settings.dwell_s));
            }
            self.queue.push_back(goto(above));
        }
    }

    /// The end of the file: the order rules, then the way home.
    fn end(&mut self) -> Result<(), PointsError> {
        if let Some((line, _)) = self.pending_pick {
            return Err(Located::at_line(line, PointsErrorKind::UnpairedPick));
        }
        if !self.started {
            return Err(Located::at_line(self.reader.line().max(1), PointsErrorKind::NoPairs));
        }
        self.queue.push_back(Statement::Rapid);
        self.queue.push_back(goto(self.settings.home));
        self.queue.push_back(Statement::End);
        self.queue.push_back(Statement::Fini);
        Ok(())
    }
}

fn goto(point: Point) -> Statement {
    Statement::Goto(Goto { x: point.x, y: point.y, z: point.z, c: Some(point.c), axis: None })
}

impl<R: BufRead> Iterator for ClProgram<'_, R> {
    type Item = Result<Statement, PointsError>;

    fn next(&mut self) -> Option<Self::Item> {
        if let Some(statement) = self.queue.pop_front() {
            return Some(Ok(statement));
        }
        match self.fill() {
            Ok(()) => self.queue.pop_front().map(Ok),
            Err(err) => {
                self.done = true;
                self.queue.clear();
                Some(Err(err))
            }
        }
    }
}

/// Reads the points file `input` and writes its CL program to `out`, streaming (`biscara clf`).
pub fn write_cl(
    input: impl BufRead,
    model: &Kinematics,
    mut out: impl Write,
) -> Result<(), WriteClError> {
    for statement in ClProgram::new(input, model) {
        write_statement(&mut out, &statement?).map_err(WriteClError::Write)?;
    }
    out.flush().map_err(WriteClError::Write)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cl(points: &str) -> Result<String, WriteClError> {
        let mut out = Vec::new();
        write_cl(points.as_bytes(), &Kinematics::default(), &mut out)?;
        Ok(String::from_utf8(out).unwrap())
    }

    #[track_caller]
    fn check_error(points: &str, message: &str) {
        let err = cl(points).expect_err(points).to_string();
        assert!(err.contains(message), "{points:?}: {err}");
    }

    #[test]
    fn one_pair_with_defaults() {
        let text = cl("pick 150 320 10 30\nplace -150 300 20 0\n").unwrap();
        assert_eq!(
            text,
            "PARTNO/PICK AND PLACE\nUNITS/MM\nRAPID\nGOTO/0.0000,460.7987,100.0000,0.0000\n\
             RAPID\nGOTO/150.0000,320.0000,60.0000,30.0000\nFEDRAT/MMPM,3000.0000\n\
             GOTO/150.0000,320.0000,10.0000,30.0000\nPICK\nGOTO/150.0000,320.0000,60.0000,30.0000\n\
             RAPID\nGOTO/-150.0000,300.0000,70.0000,0.0000\nGOTO/-150.0000,300.0000,20.0000,0.0000\n\
             PLACE\nGOTO/-150.0000,300.0000,70.0000,0.0000\n\
             RAPID\nGOTO/0.0000,460.7987,100.0000,0.0000\nEND\nFINI\n"
        );
    }

    #[test]
    fn order_rules() {
        check_error("", "1: no pick/place pair");
        check_error("# nothing\n\n", "2: no pick/place pair");
        check_error("home 0 400 100 0\n", "1: no pick/place pair");
        check_error("place -150 300 20 0\n", "1: place before pick");
        check_error("pick 150 320 10 30\n", "1: the pick on this line has no place");
        check_error(
            "pick 150 320 10 30\nplace -150 300 20 0\npick 150 320 10 30\n",
            "3: the pick on this line has no place",
        );
        check_error(
            "pick 150 320 10 30\npick 150 320 10 30\n",
            "2: pick after pick: the pick on line 1",
        );
        check_error("feed 1\nfeed 2\n", "2: `feed` is given twice (first on line 1)");
        check_error(
            "pick 150 320 10 30\napproach 20\nplace -150 300 20 0\n",
            "2: `approach` must come before the first pick (line 1)",
        );
    }

    #[test]
    fn reachability_names_the_pose_and_the_reason() {
        check_error(
            "pick 900 0 10 0\nplace -150 300 20 0\n",
            "1: pick (x, y, z, c) = (900, 0, 10, 0) is unreachable: chain 1 cannot reach",
        );
        check_error(
            "pick 150 320 70 30\nplace -150 300 20 0\n",
            "1: approach pose above the pick (x, y, z, c) = (150, 320, 120, 30) is unreachable: \
             d4 = -20.000 mm is outside its limits [0, 100] by 20.000 mm",
        );
        check_error(
            "pick 150 320 10 30\nplace -150 300 90 0\n",
            "2: approach pose above the place",
        );
        check_error("home 0 60 50 0\n", "1: home (x, y, z, c) = (0, 60, 50, 0) is unreachable");
        check_error(
            "pick 150 320 10 30\nplace 0 60 10 0\n",
            "2: place (x, y, z, c) = (0, 60, 10, 0) is unreachable: (x, y) = (0.000, 60.000) is beyond a type-2 singularity",
        );
    }
}
