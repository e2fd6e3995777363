//! The `biscara` command: a thin layer that parses flags, opens files, calls the library crates
//! and prints. See `biscara --help`.

mod cli;

fn main() -> std::process::ExitCode {
    // SIGINT, SIGTERM or SIGHUP while an output file is written: its temporary file is removed
    // (the earlier output stays), then the run ends with 130 (128 + SIGINT, as shells report an
    // interrupt). The one `process::exit`: the handler runs on its own thread.
    biscara_files::on_interrupt(|| std::process::exit(130));
    cli::main()
}
