//! The language's syntax, apart from its execution: lines and their significant characters
//! ([`lexer`]), words, blocks and expressions with LinuxCNC's operators and functions
//! ([`parser`], its trigonometry in [`degrees`]), and the numbered and named parameters
//! ([`params`]).

/// LinuxCNC's trigonometry in degrees.
pub(crate) mod degrees;
/// Lines and their significant characters.
pub(crate) mod lexer;
/// Numbered and named parameters.
pub(crate) mod params;
/// Words, blocks, expressions and modal groups.
pub(crate) mod parser;
