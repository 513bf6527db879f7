//! The `hodr` command line.

use clap::{Parser, Subcommand};

/// hodr: second-order optimisation of discontinuous, black-box renderers.
#[derive(Parser, Debug)]
#[command(version, about, long_about = None)]
struct Cli {
    #[command(subcommand)]
    command: Option<Command>,
}

#[derive(Subcommand, Debug)]
enum Command {
    /// Variance of every estimator at equal evaluation budgets (Markdown table on stdout).
    Variance {
        /// Repetitions per table cell.
        #[arg(long, default_value_t = 2000, value_parser = clap::value_parser!(u64).range(2..))]
        repeats: u64,
    },
    /// Error against run time of every preset on QUAD, BOX2-REF and stiff quadratics.
    Runtime {
        /// Seeds per problem and preset.
        #[arg(long, default_value_t = 20, value_parser = clap::value_parser!(u64).range(1..))]
        seeds: u64,
        /// Draw the paper presets' central-difference gradients with common random numbers.
        #[arg(long)]
        crn: bool,
    },
}

fn main() -> anyhow::Result<()> {
    let cli = Cli::parse();
    match cli.command.unwrap_or(Command::Variance { repeats: 2000 }) {
        Command::Variance { repeats } => {
            print!("{}", hodr_host::variance::study(repeats as usize));
        }
        Command::Runtime { seeds, crn } => {
            use hodr_core::optim::preset::Preset;
            use hodr_host::runtime::{Problem, table};
            print!("{}", table(&Problem::all(), &Preset::ALL, seeds, crn));
        }
    }
    Ok(())
}
