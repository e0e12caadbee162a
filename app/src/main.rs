//! The `cutaway` binary: parses the command line and reports errors as one line.

fn main() -> std::process::ExitCode {
    match cutaway::cli::run(std::env::args_os()) {
        Ok(()) => std::process::ExitCode::SUCCESS,
        Err(error) => {
            eprintln!("{}", cutaway::cli::error_line(&error));
            std::process::ExitCode::FAILURE
        }
    }
}
