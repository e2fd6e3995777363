//! The grid of designs: three `MIN:MAX:N` ranges, their designs in a fixed order, and shards.

use std::str::FromStr;

use crate::DesignError;

/// The most designs one sweep indexes (2³²).
pub const MAX_DESIGNS: u64 = 1 << 32;

/// `N` values from `MIN` to `MAX` inclusive, evenly spaced (`MIN:MAX:N`); `N = 1` is `MIN` alone
/// and needs `MIN = MAX`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ParamRange {
    /// The first value, millimetres.
    pub min: f64,
    /// The last value, millimetres.
    pub max: f64,
    /// How many values.
    pub count: u32,
}

impl ParamRange {
    /// Reads `MIN:MAX:N` for the parameter `what` (kept in the error): finite positive lengths,
    /// `MIN ≤ MAX`, `1 ≤ N ≤ 10000`, `N = 1` only when `MIN = MAX`.
    pub fn parse(what: &'static str, text: &str) -> Result<ParamRange, DesignError> {
        let fail = |reason: &str| DesignError::Range {
            what,
            text: text.to_owned(),
            reason: reason.to_owned(),
        };
        let parts: Vec<&str> = text.split(':').collect();
        let [min, max, count] = parts[..] else {
            return Err(fail("does not have three parts"));
        };
        let length = |part: &str, name: &str| -> Result<f64, DesignError> {
            let value: f64 = part
                .trim()
                .parse()
                .map_err(|_| fail(&format!("has a {name} that is no number")))?;
            if !value.is_finite() || value <= 0.0 {
                return Err(fail(&format!("has a {name} that is not a positive length")));
            }
            Ok(value)
        };
        let (min, max) = (length(min, "MIN")?, length(max, "MAX")?);
        let count: u32 =
            count.trim().parse().map_err(|_| fail("has an N that is no whole number"))?;
        if min > max {
            return Err(fail("has MIN above MAX"));
        }
        if !(1..=10_000).contains(&count) {
            return Err(fail("has an N outside 1..10000"));
        }
        if count == 1 && min != max {
            return Err(fail("has N = 1 but MIN ≠ MAX"));
        }
        Ok(ParamRange { min, max, count })
    }

    /// A parser of `MIN:MAX:N` for the parameter `what`, as [`ParamRange::parse`]: what a
    /// command line's flag takes.
    pub fn parser(
        what: &'static str,
    ) -> impl Fn(&str) -> Result<ParamRange, DesignError> + Clone + Send + Sync + 'static {
        move |text| ParamRange::parse(what, text)
    }

    /// A single value (`V:V:1`).
    pub fn single(value: f64) -> ParamRange {
        ParamRange { min: value, max: value, count: 1 }
    }

    /// Value `i` (from 0): `MIN + (MAX − MIN)·i/(N − 1)`, exactly `MAX` for the last.
    pub fn value(&self, i: u32) -> f64 {
        if self.count <= 1 || i == 0 {
            self.min
        } else if i + 1 >= self.count {
            self.max
        } else {
            self.min + (self.max - self.min) * f64::from(i) / f64::from(self.count - 1)
        }
    }

    /// Every value, in order.
    pub fn values(&self) -> impl Iterator<Item = f64> + '_ {
        (0..self.count).map(|i| self.value(i))
    }
}

/// One design: proximal and distal link lengths and the distance between the base joints, mm.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Design {
    /// The design's place in its grid, from 0 (base fastest, then l2, then l1).
    pub index: u64,
    /// Proximal link length, mm.
    pub l1: f64,
    /// Distal link length, mm.
    pub l2: f64,
    /// Distance between the two base joints, mm (placed at ±base/2).
    pub base: f64,
}

/// The designs of three ranges, in the order l1 (slowest), l2, base (fastest).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DesignGrid {
    /// The proximal link lengths.
    pub l1: ParamRange,
    /// The distal link lengths.
    pub l2: ParamRange,
    /// The base distances.
    pub base: ParamRange,
}

impl DesignGrid {
    /// The grid of three ranges; fails when it has more than [`MAX_DESIGNS`] designs.
    pub fn new(
        l1: ParamRange,
        l2: ParamRange,
        base: ParamRange,
    ) -> Result<DesignGrid, DesignError> {
        let count = u128::from(l1.count) * u128::from(l2.count) * u128::from(base.count);
        if count > u128::from(MAX_DESIGNS) {
            return Err(DesignError::TooManyDesigns { count, max: MAX_DESIGNS });
        }
        Ok(DesignGrid { l1, l2, base })
    }

    /// How many designs.
    pub fn len(&self) -> u64 {
        u64::from(self.l1.count) * u64::from(self.l2.count) * u64::from(self.base.count)
    }

    /// Whether the grid has no design (never: every range has a value).
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Design number `index` (< [`DesignGrid::len`]).
    pub fn design(&self, index: u64) -> Design {
        let nb = u64::from(self.base.count);
        let n2 = u64::from(self.l2.count);
        let ib = (index % nb) as u32;
        let i2 = ((index / nb) % n2) as u32;
        let i1 = (index / nb / n2) as u32;
        Design { index, l1: self.l1.value(i1), l2: self.l2.value(i2), base: self.base.value(ib) }
    }
}

/// Part `k` of `n` of a sweep (`K/N`, 1 ≤ K ≤ N): the designs whose index is `k − 1` modulo `n`.
/// Round robin, so every shard gets small and large designs alike.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Shard {
    /// Which part, from 1.
    pub k: u64,
    /// Of how many parts.
    pub n: u64,
}

impl Shard {
    /// The whole sweep (`1/1`).
    pub const ALL: Shard = Shard { k: 1, n: 1 };

    /// Whether design `index` belongs to this shard.
    pub fn contains(&self, index: u64) -> bool {
        index % self.n == self.k - 1
    }

    /// The indices of this shard's designs among `len`, in order.
    pub fn indices(&self, len: u64) -> impl Iterator<Item = u64> + use<> {
        let (first, step) = (self.k - 1, self.n);
        (first..len).step_by(usize::try_from(step).unwrap_or(usize::MAX))
    }

    /// How many of `len` designs this shard evaluates.
    pub fn count(&self, len: u64) -> u64 {
        if len < self.k { 0 } else { (len - self.k) / self.n + 1 }
    }
}

impl FromStr for Shard {
    type Err = DesignError;

    fn from_str(text: &str) -> Result<Shard, DesignError> {
        let fail =
            |reason: &str| DesignError::Shard { text: text.to_owned(), reason: reason.to_owned() };
        let (k, n) = text.split_once('/').ok_or_else(|| fail("has no '/'"))?;
        let k: u64 = k.trim().parse().map_err(|_| fail("has a K that is no whole number"))?;
        let n: u64 = n.trim().parse().map_err(|_| fail("has an N that is no whole number"))?;
        if n == 0 || k == 0 || k > n {
            return Err(fail("is not a part of the sweep"));
        }
        Ok(Shard { k, n })
    }
}

/// A task rectangle that a design must cover: every workspace grid point in it reachable.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Task {
    /// The corner with the smallest x and y, mm.
    pub min: [f64; 2],
    /// The corner with the largest x and y, mm.
    pub max: [f64; 2],
}

impl FromStr for Task {
    type Err = DesignError;

    fn from_str(text: &str) -> Result<Task, DesignError> {
        let fail =
            |reason: &str| DesignError::Task { text: text.to_owned(), reason: reason.to_owned() };
        let values: Vec<f64> = text
            .split(',')
            .map(|part| part.trim().parse::<f64>())
            .collect::<Result<_, _>>()
            .map_err(|_| fail("has a value that is no number"))?;
        let [x0, y0, x1, y1] = values[..] else {
            return Err(fail("does not have four values"));
        };
        if values.iter().any(|v| !v.is_finite()) {
            return Err(fail("has a value that is not finite"));
        }
        if x0 > x1 || y0 > y1 {
            return Err(fail("has X0 > X1 or Y0 > Y1"));
        }
        Ok(Task { min: [x0, y0], max: [x1, y1] })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ranges_read_and_refuse() {
        let r = ParamRange::parse("l1", "180:260:5").unwrap();
        assert_eq!(r.values().collect::<Vec<_>>(), [180.0, 200.0, 220.0, 240.0, 260.0]);
        assert_eq!(ParamRange::parse("l1", "200:200:1").unwrap().values().count(), 1);
        for (bad, says) in [
            ("180:260", "three parts"),
            ("a:260:5", "MIN that is no number"),
            ("180:-1:5", "MAX that is not a positive length"),
            ("180:nan:5", "MAX that is not a positive length"),
            ("260:180:5", "MIN above MAX"),
            ("180:260:0", "outside 1..10000"),
            ("180:260:2.5", "N that is no whole number"),
            ("180:260:1", "N = 1 but MIN ≠ MAX"),
        ] {
            let err = ParamRange::parse("l1", bad).unwrap_err().to_string();
            assert!(err.starts_with('\'') && err.contains(says), "{bad}: {err}");
        }
        let base = ParamRange::parser("base");
        assert_eq!(base("100:300:3").unwrap().values().collect::<Vec<_>>(), [100.0, 200.0, 300.0]);
        let err = base("300:100:3").unwrap_err();
        assert!(matches!(err, DesignError::Range { what: "base", .. }), "{err}");
    }

    #[test]
    fn designs_run_base_fastest_and_shards_split_them() {
        let grid = DesignGrid::new(
            ParamRange::parse("l1", "1:2:2").unwrap(),
            ParamRange::parse("l2", "10:30:3").unwrap(),
            ParamRange::parse("base", "100:400:4").unwrap(),
        )
        .unwrap();
        assert_eq!(grid.len(), 24);
        let d = grid.design(13);
        assert_eq!((d.l1, d.l2, d.base), (2.0, 10.0, 200.0));
        let shards: Vec<Shard> = (1..=5).map(|k| format!("{k}/5").parse().unwrap()).collect();
        let mut seen: Vec<u64> = shards.iter().flat_map(|s| s.indices(grid.len())).collect();
        seen.sort_unstable();
        assert_eq!(seen, (0..24).collect::<Vec<_>>());
        for shard in &shards {
            assert_eq!(shard.count(24), shard.indices(24).count() as u64);
            assert!(shard.indices(24).all(|i| shard.contains(i)));
        }
        for bad in ["0/3", "4/3", "1/0", "x/3", "3"] {
            assert!(bad.parse::<Shard>().is_err(), "{bad}");
        }
    }

    #[test]
    fn tasks_read_and_refuse() {
        let task: Task = "-100, 300,100,400".parse().unwrap();
        assert_eq!(task, Task { min: [-100.0, 300.0], max: [100.0, 400.0] });
        for bad in ["1,2,3", "1,2,3,x", "5,0,1,1", "0,0,inf,1"] {
            assert!(bad.parse::<Task>().is_err(), "{bad}");
        }
    }
}
