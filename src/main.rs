use seasynth::error::exit;

fn main() {
    let cli = seasynth::cli::Cli::parse_ordered();
    // SIGINT/SIGTERM remove every temporary file of every command before exiting.
    if let Err(e) = seasynth::export::live::install() {
        eprintln!("Error: cannot watch for interruptions: {e}");
        std::process::exit(exit::FAILED);
    }
    if let Err(e) = seasynth::commands::run(cli) {
        eprintln!("Error: {e:#}");
        let usage = e
            .downcast_ref::<seasynth::error::Error>()
            .is_some_and(|e| e.is_usage());
        std::process::exit(if usage { exit::USAGE } else { exit::FAILED });
    }
}
