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
}

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
        let mut named: Vec<(Vec<u8>, u64)> =
            self.named.iter().map(|(name, value)| (name.clone(), value.to_bits())).collect();
        named.sort_unstable();
        ParamsSnapshot {
            changes: self.changes,
            numbered: self.numbered.iter().map(|value| value.to_bits()).collect(),
            named,
        }
    }

    /// Whether every value is what it was at `snapshot` (bit for bit).
    pub(crate) fn same_as(&self, snapshot: &ParamsSnapshot) -> bool {
        if snapshot.changes == self.changes {
            return true;
        }
        self.numbered.iter().zip(&snapshot.numbered).all(|(value, bits)| value.to_bits() == *bits)
            && self.named.len() == snapshot.named.len()
            && snapshot
                .named
                .iter()
                .all(|(name, bits)| self.named.get(name).is_some_and(|v| v.to_bits() == *bits))
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
            }
            None => {
                self.named.insert(name.to_vec(), value);
                self.changes += 1;
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
        self.named.retain(|name, _| name.first() == Some(&b'_'));
        self.named.extend(locals);
    }
}
