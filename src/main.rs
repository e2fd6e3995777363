//! The `biscara` command: a thin layer that parses flags, opens files, calls the library crates
//! and prints. See `biscara --help`.

mod cli;

fn main() -> std::process::ExitCode {
    // SIGINT, SIGTERM or SIGHUP while an output file is written: its temporary file is removed
    // (the earlier output stays), then the run ends with 130 (128 + SIGINT, as shells report an
    // interrupt). The one `process::exit`: the handler runs on its own thread.
    // During a LinuxCNC run the run itself stops LinuxCNC, removes its folders and ends with
    // 130: this thread then waits for that.
    biscara_files::on_interrupt(|| {
        if biscara::linuxcnc::runner::interrupt() {
            loop {
                std::thread::park();
            }
        }
        std::process::exit(130)
    });
    cli::main()
}
