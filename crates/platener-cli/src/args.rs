//! Command-line flags (clap), and their translation into [`platener::Settings`].

use std::path::PathBuf;

use clap::{Args, Parser, Subcommand};

use crate::setting_args::{Every, ForMaterial, ForModel, ForScene, ForVerify, SettingArgs};

/// Examples shown under `platener --help`.
const MAIN_EXAMPLES: &str = "Examples:
  platener convert examples/box-3mm.stl -o out
  platener convert models/ -o out -t 3 -t 6 --method plate -j 4
  platener inspect examples/box-3mm.stl --plates
  platener test-strip -t 3 -o strip.svg
  platener serve --addr 127.0.0.1:3000 --workers 2
  platener completions bash > /etc/bash_completion.d/platener

Exit codes: 0 success; 1 something failed: for convert, a model that no method converted or an
input that gave no model (every other model is still converted and reported; a method that fails
on a model another method converted is reported, the model as partial, and exits 0); for verify,
a check that failed; for inspect and test-strip, a model or file that could not be read or
written; 2 a usage error.";

/// Turns 3D-printing models (STL, OBJ, 3MF) into laser-cut construction plans.
#[derive(Debug, Parser)]
#[command(name = "platener", version, about, long_about = None, after_help = MAIN_EXAMPLES)]
pub struct Cli {
    /// What to do.
    #[command(subcommand)]
    pub command: Command,
}

/// The subcommands.
#[derive(Debug, Subcommand)]
pub enum Command {
    /// Converts models (files, or folders searched recursively) into cutting-plan ZIPs, one
    /// per model and method, and reports what went right and wrong.
    #[command(after_help = crate::convert::EXAMPLES)]
    Convert(Box<ConvertArgs>),
    /// Reads a model and reports what platener sees in it: mesh health, welding, planar shapes.
    #[command(
        after_help = "Examples:\n  platener inspect examples/box-3mm.stl\n  platener inspect part.obj --units in --json"
    )]
    Inspect(InspectArgs),
    /// Draws a kerf test strip: cut it, push the spike into the holes, read the kerf of the
    /// hole it fits snugly.
    #[command(
        name = "test-strip",
        after_help = "Examples:\n  platener test-strip -t 3 -o strip.svg\n  platener test-strip -t 4 --material acrylic -o strip.svg"
    )]
    TestStrip(TestStripArgs),
    /// Draws a bend swatch: a strip with two flat ends and one designed bend (living-hinge
    /// slits, a perforation, a score or a heat line) at true size, with its figures engraved,
    /// to check that the material bends as designed before cutting a whole part.
    #[command(
        name = "hinge-test",
        after_help = "Examples:\n  platener hinge-test -t 3 -m wood -o hinge.svg\n  platener hinge-test -t 1.5 -m cardboard --angle 60\n  platener hinge-test -t 3 -m acrylic --bend living-hinge"
    )]
    HingeTest(HingeTestArgs),
    /// Rebuilds the assembly from a cutting plan and checks it: parts that intersect, parts
    /// that fall apart, joints whose parts do not meet, invalid outlines, parts outside or
    /// larger than their sheet, and (with the model) how much of the model the parts
    /// reproduce. Prints each failure with its part ids; exits 1 when a check fails.
    #[command(
        after_help = "Examples:\n  platener verify out/box-3mm-plate.zip\n  platener verify out/box-3mm-plate.zip --model examples/box-3mm.stl --json"
    )]
    Verify(VerifyArgs),
    /// Writes one view of a conversion as a 3D scene (glTF binary, .glb) for any viewer: the
    /// model as read, its edges, its planar groups, the plates, the bent parts, or the final
    /// assembly of the cut parts.
    #[command(after_help = crate::scene::EXAMPLES)]
    Scene(SceneArgs),
    /// Serves the web API (and page) on a port, with conversions queued in a database and run
    /// by worker processes it starts.
    #[command(after_help = crate::web::SERVE_EXAMPLES)]
    Serve(crate::web::ServeArgs),
    /// Takes conversions from the web service's queue and runs them (started by `serve`, or
    /// on other machines sharing a PostgreSQL database).
    Worker(crate::web::WorkerArgs),
    /// Prints a shell completion script.
    #[command(after_help = crate::completions::EXAMPLES)]
    Completions(CompletionsArgs),
}

/// `platener scene`.
#[derive(Debug, Args)]
pub struct SceneArgs {
    /// The model file (.stl, .obj, .3mf).
    pub model: PathBuf,
    /// The view: model, wireframe, coplanar, primitives, plates, bent or final.
    #[arg(long, default_value = "final")]
    pub view: String,
    /// The .glb file to write.
    #[arg(short = 'o', long = "output", value_name = "FILE.glb")]
    pub output: PathBuf,
    /// The settings (`--method all`: the best method's snapshots are drawn).
    #[command(flatten)]
    pub settings: SettingArgs<ForScene>,
}

/// `platener verify`.
#[derive(Debug, Args)]
pub struct VerifyArgs {
    /// The cutting plan: a ZIP written by `platener convert`.
    pub plan: PathBuf,
    /// The model the plan was made from, to measure how much of it the parts reproduce.
    #[arg(long)]
    pub model: Option<PathBuf>,
    /// Print one JSON object instead of text.
    #[arg(long)]
    pub json: bool,
    /// With --model: the share of the model's surface (percent) the parts must come within
    /// half a sheet plus 0.5 mm of.
    #[arg(long, value_name = "PERCENT", default_value_t = 80.0, value_parser = parse_percent)]
    pub min_coverage: f64,
    /// How the model is read.
    #[command(flatten)]
    pub settings: SettingArgs<ForVerify>,
}

/// `platener completions`.
#[derive(Debug, Args)]
pub struct CompletionsArgs {
    /// The shell.
    #[arg(value_enum)]
    pub shell: clap_complete::Shell,
}

/// `platener test-strip`.
#[derive(Debug, Args)]
pub struct TestStripArgs {
    /// Sheet thickness in mm.
    #[arg(short = 't', long = "thickness")]
    pub thickness: f64,
    /// The material (its kerf is the strip's starred hole).
    #[command(flatten)]
    pub material: SettingArgs<ForMaterial>,
    /// Where to write the SVG.
    #[arg(short = 'o', long = "output")]
    pub output: PathBuf,
}

/// `platener hinge-test`.
#[derive(Debug, Args)]
pub struct HingeTestArgs {
    /// Sheet thickness in mm.
    #[arg(short = 't', long = "thickness")]
    pub thickness: f64,
    /// The material.
    #[command(flatten)]
    pub material: SettingArgs<ForMaterial>,
    /// The bend style: auto (the material's: wood → living-hinge, cardboard → perforation,
    /// paper → score, acrylic → heat), living-hinge, perforation, score or heat.
    #[arg(long, default_value = "auto", value_parser = parse_bend_style)]
    pub bend: platener::Bending,
    /// How far the bend turns, degrees (90 = a square corner, 180 = a U-turn).
    #[arg(long, default_value_t = 90.0)]
    pub angle: f64,
    /// Where to write the SVG.
    #[arg(short = 'o', long = "output", default_value = "hinge-test.svg")]
    pub output: PathBuf,
}

/// `--bend` of hinge-test: a style or `auto`; `none` would draw no bend.
fn parse_bend_style(s: &str) -> Result<platener::Bending, String> {
    match s.parse::<platener::Bending>().map_err(|e| e.to_string())? {
        platener::Bending::None => Err("a swatch needs a bend style, not none".into()),
        bending => Ok(bending),
    }
}

/// `platener inspect`.
#[derive(Debug, Args)]
pub struct InspectArgs {
    /// The model file (.stl, .obj, .3mf).
    pub model: PathBuf,
    /// Print one JSON object instead of text.
    #[arg(long)]
    pub json: bool,
    /// Also find the plates (for the thicknesses given with -t) and report which faces became
    /// plates and why the others did not.
    #[arg(long)]
    pub plates: bool,
    /// Find inherent plates only (no extruded plates); implies --plates.
    #[arg(long)]
    pub inherent_only: bool,
    /// How the model is read.
    #[command(flatten)]
    pub settings: SettingArgs<ForModel>,
}

fn parse_percent(s: &str) -> Result<f64, String> {
    match s.trim().trim_end_matches('%').parse::<f64>() {
        Ok(p) if (0.0..=100.0).contains(&p) => Ok(p),
        _ => Err(format!("{s:?} is not a percentage from 0 to 100")),
    }
}

fn parse_jobs(s: &str) -> Result<usize, String> {
    match s.parse::<usize>() {
        Ok(n) if n >= 1 => Ok(n),
        _ => Err(format!("{s:?} is not a number of jobs ≥ 1")),
    }
}

fn parse_non_negative(s: &str) -> Result<f64, String> {
    match s.parse::<f64>() {
        Ok(v) if v.is_finite() && v >= 0.0 => Ok(v),
        _ => Err(format!("{s:?} is not a number ≥ 0")),
    }
}

/// `platener convert`.
#[derive(Debug, Args)]
pub struct ConvertArgs {
    /// Model files (.stl, .obj, .3mf) and folders (searched recursively, in name order).
    #[arg(required = true, value_name = "INPUT")]
    pub inputs: Vec<PathBuf>,
    /// Folder the ZIPs are written to, as OUT_DIR/<model>-<method>.zip (created if missing).
    #[arg(short = 'o', long = "output", value_name = "OUT_DIR")]
    pub output: PathBuf,
    /// Skip (and list) model files larger than this many MB (10^6 bytes).
    #[arg(long, value_name = "MB", value_parser = parse_non_negative)]
    pub max_filesize: Option<f64>,
    /// Models converted at the same time (default: one per core).
    #[arg(short = 'j', long, value_name = "N", value_parser = parse_jobs)]
    pub jobs: Option<usize>,
    /// Give up a method after this many seconds (each method's own limit; they run side by side); 0: never.
    #[arg(long, value_name = "S", default_value_t = 60.0, value_parser = parse_non_negative)]
    pub timeout: f64,
    /// More output: warnings of every model, step progress and logs (-vv: debug logs).
    #[arg(short = 'v', long, action = clap::ArgAction::Count)]
    pub verbose: u8,
    /// Also write OUT_DIR/<model>-<method>.report.json for every model and method: the score,
    /// warnings or error, and the cutting plan's report.json.
    #[arg(long)]
    pub sub_reports: bool,
    /// Print the batch report as one JSON object on stdout instead of text.
    #[arg(long)]
    pub json: bool,
    /// The settings.
    #[command(flatten)]
    pub settings: SettingArgs<Every>,
}

#[cfg(test)]
mod tests {
    use clap::Parser as _;
    use platener::Bending;
    use platener::plan::BendStyle;

    use super::{Cli, Command};

    fn bend_of(extra: &[&str]) -> anyhow::Result<Bending> {
        let args = ["platener", "convert", "m.stl", "-o", "out"].iter().chain(extra);
        match Cli::try_parse_from(args)?.command {
            Command::Convert(c) => Ok(c.settings.chosen()?.settings.bending),
            other => panic!("parsed as {other:?}"),
        }
    }

    #[test]
    fn bend_takes_every_style_and_defaults_to_auto() {
        assert_eq!(bend_of(&[]).expect("valid"), Bending::Auto);
        assert_eq!(bend_of(&["--bend", "none"]).expect("valid"), Bending::None);
        for (name, style) in [
            ("living-hinge", BendStyle::LivingHinge),
            ("perforation", BendStyle::Perforation),
            ("score", BendStyle::Score),
            ("heat", BendStyle::Heat),
        ] {
            assert_eq!(bend_of(&["--bend", name]).expect("valid"), Bending::Style(style));
        }
        let e = bend_of(&["--bend", "fold"]).expect_err("unknown style").to_string();
        assert!(e.contains("--bend") && e.contains("living-hinge"), "{e}");
    }

    /// Every command's flags are consistent (no name twice, defaults among the values).
    #[test]
    fn the_command_line_is_well_formed() {
        use clap::CommandFactory as _;
        Cli::command().debug_assert();
    }

    /// Out-of-range values are refused by the library's check, named as flags.
    #[test]
    fn refusals_name_the_flag() {
        for (flag, value) in [
            ("--kerf", "3"),
            ("--thickness", "0.05"),
            ("--scale", "0"),
            ("--weld", "11"),
        ] {
            let e = bend_of(&[flag, value]).expect_err("out of range").to_string();
            assert!(e.starts_with(flag), "{flag} {value}: {e}");
        }
    }
}
