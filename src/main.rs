//! The `biscara` command: a thin layer that parses flags, opens files, calls the library crates
//! and prints. See `biscara --help`.

mod cli;

fn main() -> std::process::ExitCode {
    cli::main()
}
