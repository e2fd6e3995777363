//! Parameters: numbered (`#1` … `#5601`) and named (`#<name>` local, `#<_name>` global).

use std::collections::HashMap;

/// LinuxCNC's `RS274NGC_MAX_PARAMETERS`: numbered parameters are `1..MAX_PARAMETERS`.
pub(crate) const MAX_PARAMETERS: usize = 5602;

/// First parameter of G28's stored position (x y z a b c u v w follow).
pub(crate) const G28_HOME: usize = 5161;
/// First parameter of G30's stored position.
pub(crate) const G30_HOME: usize = 5181;
/// G92 offsets applied (1) or not (0).
pub(crate) const G92_ENABLED: usize = 5210;
/// First parameter of the G92 offsets.
pub(crate) const G92_OFFSET: usize = 5211;
/// The active coordinate system, 1 (G54) … 9 (G59.3).
pub(crate) const COORDINATE_SYSTEM: usize = 5220;

/// First parameter of coordinate system `system` (1 = G54 … 9 = G59.3); x at +0, c at +5, the
/// rotation R at +9.
pub(crate) fn coordinate_system_base(system: usize) -> usize {
    5221 + 20 * (system - 1)
}

/// Index within a block of 9 axis parameters (x y z a b c u v w) of our axis `axis` (0 = x,
/// 1 = y, 2 = z, 3 = c).
pub(crate) fn axis_slot(axis: usize) -> usize {
    [0, 1, 2, 5][axis]
}

/// All parameter values.
#[derive(Debug)]
pub(crate) struct Params {
    numbered: Box<[f64]>,
    named: HashMap<Vec<u8>, f64>,
    /// How many times a value changed (or the local names were swapped): equal counts at two
    /// moments mean no parameter changed in between (an endless loop's test).
    changes: u64,
    /// The last numbered changes: the count after each and the parameter (at most
    /// [`CHANGE_LOG`], oldest first), so that a snapshot is compared and brought up to date at
    /// those parameters only.
    log: std::collections::VecDeque<(u64, u32)>,
    /// The count after the last change of a named parameter (or of the local names).
    named_changed: u64,
}

/// How many numbered changes [`Params`] remembers.
const CHANGE_LOG: usize = 256;

/// The parameters' values at one moment ([`Params::snapshot`]).
#[derive(Debug)]
pub(crate) struct ParamsSnapshot {
    /// The change count then: the same count now means nothing changed.
    changes: u64,
    /// The numbered values' bits.
    numbered: Box<[u64]>,
    /// The named values' bits, by name.
    named: Vec<(Vec<u8>, u64)>,
}

impl Params {
    pub(crate) fn new() -> Params {
        Params {
            numbered: vec![0.0; MAX_PARAMETERS].into_boxed_slice(),
            named: HashMap::new(),
            changes: 0,
            log: std::collections::VecDeque::with_capacity(CHANGE_LOG),
            named_changed: 0,
        }
    }

    /// Numbered parameter `index` (checked by the caller to lie in `1..MAX_PARAMETERS`).
    pub(crate) fn get(&self, index: usize) -> f64 {
        self.numbered.get(index).copied().unwrap_or(0.0)
    }

    /// Sets numbered parameter `index`.
    pub(crate) fn set(&mut self, index: usize, value: f64) {
        if let Some(slot) = self.numbered.get_mut(index)
            && slot.to_bits() != value.to_bits()
        {
            *slot = value;
            self.changes += 1;
            if self.log.len() == CHANGE_LOG {
                self.log.pop_front();
            }
            self.log.push_back((self.changes, index as u32));
        }
    }

    /// Sets numbered parameter `index` to a value that mirrors state kept elsewhere (the
    /// current position, #5420…): not counted as a change, since that state is compared
    /// itself.
    pub(crate) fn set_mirror(&mut self, index: usize, value: f64) {
        if let Some(slot) = self.numbered.get_mut(index) {
            *slot = value;
        }
    }

    /// The values as they are now, to compare with later ([`Params::same_as`]).
    pub(crate) fn snapshot(&self) -> ParamsSnapshot {
        ParamsSnapshot {
            changes: self.changes,
            numbered: self.numbered.iter().map(|value| value.to_bits()).collect(),
            named: self.named_snapshot(),
        }
    }

    /// The numbered parameters changed since `snapshot`, when the log still holds them all.
    fn changed_since(&self, snapshot: &ParamsSnapshot) -> Option<impl Iterator<Item = usize>> {
        let covered = self.changes - snapshot.changes <= self.log.len() as u64;
        covered.then(|| {
            let since = snapshot.changes;
            let changed = self.log.iter().filter(move |&&(count, _)| count > since);
            changed.map(|&(_, index)| index as usize)
        })
    }

    /// Whether every value is what it was at `snapshot` (bit for bit): only the parameters
    /// changed since are compared, while the log holds them.
    pub(crate) fn same_as(&self, snapshot: &ParamsSnapshot) -> bool {
        if snapshot.changes == self.changes {
            return true;
        }
        let named_same = self.named_changed <= snapshot.changes || {
            self.named.len() == snapshot.named.len()
                && snapshot
                    .named
                    .iter()
                    .all(|(name, bits)| self.named.get(name).is_some_and(|v| v.to_bits() == *bits))
        };
        let same_bits = |index: usize| self.numbered[index].to_bits() == snapshot.numbered[index];
        named_same
            && match self.changed_since(snapshot) {
                Some(mut changed) => changed.all(same_bits),
                None => (0..self.numbered.len()).all(same_bits),
            }
    }

    /// Brings `snapshot` up to the values now (only the parameters changed since, while the log
    /// holds them).
    pub(crate) fn refresh(&self, snapshot: &mut ParamsSnapshot) {
        let changed: Option<Vec<usize>> = self.changed_since(snapshot).map(Iterator::collect);
        match changed {
            Some(changed) => {
                for index in changed {
                    snapshot.numbered[index] = self.numbered[index].to_bits();
                }
            }
            None => {
                for (bits, value) in snapshot.numbered.iter_mut().zip(self.numbered.iter()) {
                    *bits = value.to_bits();
                }
            }
        }
        if self.named_changed > snapshot.changes {
            snapshot.named = self.named_snapshot();
        }
        snapshot.changes = self.changes;
    }

    /// The named values' bits, sorted by name.
    fn named_snapshot(&self) -> Vec<(Vec<u8>, u64)> {
        let mut named: Vec<(Vec<u8>, u64)> =
            self.named.iter().map(|(name, value)| (name.clone(), value.to_bits())).collect();
        named.sort_unstable();
        named
    }

    /// A named parameter set by the program, if it was.
    pub(crate) fn named(&self, name: &[u8]) -> Option<f64> {
        self.named.get(name).copied()
    }

    /// Sets a named parameter (allocates only the first time a name is set).
    pub(crate) fn set_named(&mut self, name: &[u8], value: f64) {
        match self.named.get_mut(name) {
            Some(slot) if slot.to_bits() == value.to_bits() => {}
            Some(slot) => {
                *slot = value;
                self.changes += 1;
                self.named_changed = self.changes;
            }
            None => {
                self.named.insert(name.to_vec(), value);
                self.changes += 1;
                self.named_changed = self.changes;
            }
        }
    }

    /// The named parameters set, sorted: the global ones (`_…`) or the local ones.
    #[cfg_attr(not(feature = "python"), allow(dead_code))]
    pub(crate) fn names(&self, global: bool) -> Vec<String> {
        let mut names: Vec<String> = self
            .named
            .keys()
            .filter(|name| (name.first() == Some(&b'_')) == global)
            .map(|name| String::from_utf8_lossy(name).into_owned())
            .collect();
        names.sort_unstable();
        names
    }

    /// Takes out the local named parameters (names not starting with `_`): a subroutine call
    /// hides its caller's locals, as LinuxCNC's call frames do.
    pub(crate) fn take_locals(&mut self) -> HashMap<Vec<u8>, f64> {
        self.changes += 1;
        self.named_changed = self.changes;
        let mut locals = HashMap::new();
        self.named.retain(|name, value| {
            if name.first() == Some(&b'_') {
                return true;
            }
            locals.insert(name.clone(), *value);
            false
        });
        locals
    }

    /// Puts back locals taken by [`Params::take_locals`] (after dropping the current ones).
    pub(crate) fn restore_locals(&mut self, locals: HashMap<Vec<u8>, f64>) {
        self.changes += 1;
        self.named_changed = self.changes;
        self.named.retain(|name, _| name.first() == Some(&b'_'));
        self.named.extend(locals);
    }
}
