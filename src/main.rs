//! The `layertrace` command-line tool: parse arguments, call the library, report.

mod cli;

fn main() -> std::process::ExitCode {
    cli::main(std::env::args_os())
}
