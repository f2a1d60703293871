use clap::Parser;

fn main() {
    let cli = seasynth::cli::Cli::parse();
    if let Err(e) = seasynth::app::run(cli) {
        eprintln!("Error: {e:#}");
        let usage = e
            .downcast_ref::<seasynth::error::Error>()
            .is_some_and(|e| e.is_usage());
        std::process::exit(if usage { 2 } else { 1 });
    }
}
