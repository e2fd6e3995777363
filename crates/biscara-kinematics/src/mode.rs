//! Signs, working modes and assembly modes (docs/kinematics.md).

use std::fmt;
use std::str::FromStr;

use serde::{Deserialize, Deserializer, Serialize, Serializer};

/// The sign of a 2-D cross product: which way a linkage is bent.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Sign {
    /// Counter-clockwise (cross product ≥ 0), written `+`.
    Plus,
    /// Clockwise (cross product < 0), written `-`.
    Minus,
}

impl Sign {
    /// The sign of `value`; zero counts as [`Sign::Plus`].
    pub fn of(value: f64) -> Sign {
        if value < 0.0 { Sign::Minus } else { Sign::Plus }
    }

    /// `+1.0` or `-1.0`.
    pub fn factor(self) -> f64 {
        match self {
            Sign::Plus => 1.0,
            Sign::Minus => -1.0,
        }
    }

    /// The sign as written in files: `'+'` or `'-'`.
    pub fn symbol(self) -> char {
        match self {
            Sign::Plus => '+',
            Sign::Minus => '-',
        }
    }

    fn from_symbol(symbol: char) -> Option<Sign> {
        match symbol {
            '+' => Some(Sign::Plus),
            '-' => Some(Sign::Minus),
            _ => None,
        }
    }
}

impl fmt::Display for Sign {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.symbol())
    }
}

/// The working mode of the five-bar: the bend of each chain,
/// `σ_i = sign((E_i − b_i) × (P − E_i))`, written as two signs (`"+-"` is σ1 = +, σ2 = −).
///
/// IK picks each chain's root by this mode; the robot cannot leave it without passing a type-1
/// (serial) singularity.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct WorkingMode {
    /// σ1, the bend of chain 1 (base joint at `b1x`).
    pub chain1: Sign,
    /// σ2, the bend of chain 2 (base joint at `b2x`).
    pub chain2: Sign,
}

impl WorkingMode {
    /// All four working modes, in the order `++ +- -+ --`.
    pub const ALL: [WorkingMode; 4] = [
        WorkingMode::new(Sign::Plus, Sign::Plus),
        WorkingMode::new(Sign::Plus, Sign::Minus),
        WorkingMode::new(Sign::Minus, Sign::Plus),
        WorkingMode::new(Sign::Minus, Sign::Minus),
    ];

    /// The mode with σ1 = `chain1` and σ2 = `chain2`.
    pub const fn new(chain1: Sign, chain2: Sign) -> WorkingMode {
        WorkingMode { chain1, chain2 }
    }

    /// σ of chain `chain`.
    pub fn of(self, chain: crate::Chain) -> Sign {
        match chain {
            crate::Chain::One => self.chain1,
            crate::Chain::Two => self.chain2,
        }
    }
}

impl Default for WorkingMode {
    /// `"+-"`, the mode of the home pose of the default robot.
    fn default() -> Self {
        WorkingMode::new(Sign::Plus, Sign::Minus)
    }
}

impl fmt::Display for WorkingMode {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}{}", self.chain1, self.chain2)
    }
}

/// The error of parsing a mode string.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("unknown {what} `{text}`, expected one of {expected}")]
pub struct ParseModeError {
    what: &'static str,
    text: String,
    expected: &'static str,
}

impl FromStr for WorkingMode {
    type Err = ParseModeError;

    fn from_str(text: &str) -> Result<Self, Self::Err> {
        let mut symbols = text.chars().map(Sign::from_symbol);
        match (symbols.next(), symbols.next(), symbols.next()) {
            (Some(Some(chain1)), Some(Some(chain2)), None) => Ok(WorkingMode::new(chain1, chain2)),
            _ => Err(ParseModeError {
                what: "working mode",
                text: text.to_owned(),
                expected: "\"++\", \"+-\", \"-+\", \"--\"",
            }),
        }
    }
}

/// The assembly mode of the five-bar: `σ_a = sign((P − E2) × (P − E1))`, written `+` or `-`.
///
/// FK picks the platform point by it. The robot cannot change it without passing a type-2
/// (parallel) singularity, so a pose whose IK solution has the other assembly mode is unreachable.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct AssemblyMode(pub Sign);

impl Default for AssemblyMode {
    /// `"+"`, the mode of the home pose of the default robot.
    fn default() -> Self {
        AssemblyMode(Sign::Plus)
    }
}

impl fmt::Display for AssemblyMode {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        self.0.fmt(f)
    }
}

impl FromStr for AssemblyMode {
    type Err = ParseModeError;

    fn from_str(text: &str) -> Result<Self, Self::Err> {
        let mut symbols = text.chars().map(Sign::from_symbol);
        match (symbols.next(), symbols.next()) {
            (Some(Some(sign)), None) => Ok(AssemblyMode(sign)),
            _ => Err(ParseModeError {
                what: "assembly mode",
                text: text.to_owned(),
                expected: "\"+\", \"-\"",
            }),
        }
    }
}

macro_rules! serde_as_string {
    ($type:ty) => {
        impl Serialize for $type {
            fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
                serializer.collect_str(self)
            }
        }

        impl<'de> Deserialize<'de> for $type {
            fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
                let text = String::deserialize(deserializer)?;
                text.parse().map_err(serde::de::Error::custom)
            }
        }
    };
}

serde_as_string!(WorkingMode);
serde_as_string!(AssemblyMode);

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn modes_round_trip_through_text() {
        for mode in WorkingMode::ALL {
            assert_eq!(mode.to_string().parse::<WorkingMode>(), Ok(mode));
        }
        assert_eq!("-".parse::<AssemblyMode>(), Ok(AssemblyMode(Sign::Minus)));
        assert_eq!(WorkingMode::default().to_string(), "+-");
    }

    #[test]
    fn bad_mode_strings_are_rejected() {
        for text in ["", "+", "+-+", "+x", "pm"] {
            let err = text.parse::<WorkingMode>().unwrap_err();
            assert!(err.to_string().contains("unknown working mode"), "{err}");
        }
        for text in ["", "++", "0"] {
            assert!(text.parse::<AssemblyMode>().is_err(), "{text}");
        }
    }
}
