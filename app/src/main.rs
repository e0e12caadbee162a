//! The `cutaway` binary: parses the command line and reports errors as one line.

fn main() -> std::process::ExitCode {
    give_window_libraries_a_runtime_dir();
    match cutaway::cli::run(std::env::args_os()) {
        Ok(()) => std::process::ExitCode::SUCCESS,
        Err(error) => {
            eprintln!("{}", cutaway::cli::error_line(&error));
            std::process::ExitCode::FAILURE
        }
    }
}

/// Sets `XDG_RUNTIME_DIR` to a private folder when it is unset or invalid, so that the window
/// system libraries loaded at GPU instance creation stay quiet (see
/// [`cutaway::render::headless::private_runtime_dir`]).
#[allow(unsafe_code)]
fn give_window_libraries_a_runtime_dir() {
    if let Some(dir) = cutaway::render::headless::private_runtime_dir() {
        // SAFETY: `set_var` is unsound only while another thread reads or writes the
        // environment; this runs first thing in `main`, before any thread is started.
        unsafe { std::env::set_var("XDG_RUNTIME_DIR", dir) };
    }
}
