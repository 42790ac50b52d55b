//! Command-line flags (clap), and their translation into [`platener::Settings`].

use std::path::PathBuf;

use clap::{Args, Parser, Subcommand, ValueEnum};
use platener::method::MethodKind;
use platener::plan::{LabelMode, Material, SheetSize};
use platener::{Settings, Units, Weld};
use serde::Serialize;

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
    /// The method whose snapshots are drawn (`all`: the best by score).
    #[arg(long, value_enum, default_value = "all")]
    pub method: MethodArg,
    /// The sheet material (decides the default joint).
    #[arg(short = 'm', long, value_enum, default_value = "wood")]
    pub material: MaterialArg,
    /// The joint type.
    #[arg(long, value_enum, default_value = "auto")]
    pub joint: JointArg,
    /// The stacked method's slicing direction.
    #[arg(long, value_name = "x|y|z|auto", default_value = "auto")]
    pub axis: String,
    /// Model options.
    #[command(flatten)]
    pub model_args: ModelArgs,
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
    /// Options for reading the model.
    #[command(flatten)]
    pub model_args: ModelArgs,
}

/// `platener completions`.
#[derive(Debug, Args)]
pub struct CompletionsArgs {
    /// The shell.
    #[arg(value_enum)]
    pub shell: clap_complete::Shell,
}

/// The sheet material (sets the default kerf the strip marks with `*`).
#[derive(Debug, Clone, Copy, ValueEnum)]
pub enum MaterialArg {
    /// Acrylic (PMMA), default kerf 0.15 mm.
    Acrylic,
    /// Plywood, MDF, solid wood, default kerf 0.2 mm.
    Wood,
    /// Cardboard, default kerf 0.3 mm.
    Cardboard,
    /// Paper and thin card, default kerf 0.1 mm.
    Paper,
}

impl MaterialArg {
    /// The library's material.
    pub fn material(self) -> Material {
        match self {
            MaterialArg::Acrylic => Material::Acrylic,
            MaterialArg::Wood => Material::Wood,
            MaterialArg::Cardboard => Material::Cardboard,
            MaterialArg::Paper => Material::Paper,
        }
    }
}

/// `platener test-strip`.
#[derive(Debug, Args)]
pub struct TestStripArgs {
    /// Sheet thickness in mm.
    #[arg(short = 't', long = "thickness")]
    pub thickness: f64,
    /// The material.
    #[arg(long, value_enum, default_value = "wood")]
    pub material: MaterialArg,
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
    #[arg(short = 'm', long, value_enum, default_value = "wood")]
    pub material: MaterialArg,
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

/// The unit of a model file's numbers.
#[derive(Debug, Clone, Copy, ValueEnum)]
pub enum UnitArg {
    /// Millimetres (default; STL has no unit).
    Mm,
    /// Centimetres.
    Cm,
    /// Inches.
    In,
}

/// Options shared by every command that reads a model.
#[derive(Debug, Args)]
pub struct ModelArgs {
    /// The unit the model's numbers are in.
    #[arg(long, value_enum, default_value = "mm")]
    pub units: UnitArg,
    /// Extra scale factor applied after the unit conversion.
    #[arg(long, default_value_t = 1.0)]
    pub scale: f64,
    /// Weld distance in mm (`auto`: from the model size, at most 2 mm; `0`: exact duplicates only).
    #[arg(long, default_value = "auto")]
    pub weld: String,
    /// Sheet thickness in mm; repeat for several.
    #[arg(short = 't', long = "thickness", default_values_t = [3.0])]
    pub thickness: Vec<f64>,
    /// Plate method: features on one face of a plate that do not go through it (engraved text,
    /// pockets, standoff footprints) are scored on it (`engrave`), cut through (`cut`, the
    /// behaviour before) or left out of a solid plate (`ignore`).
    #[arg(long, value_name = "engrave|cut|ignore", default_value = "engrave")]
    pub features: String,
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
    /// Model options.
    #[command(flatten)]
    pub model_args: ModelArgs,
}

impl ModelArgs {
    /// The library settings these flags ask for.
    pub fn settings(&self) -> anyhow::Result<Settings> {
        let weld = match self.weld.trim() {
            "auto" => Weld::Auto,
            s => match s.parse::<f64>() {
                Ok(0.0) => Weld::Off,
                Ok(d) => Weld::Distance(d),
                Err(_) => anyhow::bail!("--weld takes `auto` or a distance in mm, not {s:?}"),
            },
        };
        let settings = Settings {
            units: match self.units {
                UnitArg::Mm => Units::Mm,
                UnitArg::Cm => Units::Cm,
                UnitArg::In => Units::In,
            },
            scale: self.scale,
            weld,
            thicknesses: self.thickness.clone(),
            features: self.features.parse().map_err(|e| anyhow::anyhow!("--features: {e}"))?,
            ..Settings::default()
        };
        settings.validate()?;
        Ok(settings)
    }
}

/// Which methods `convert` runs.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum MethodArg {
    /// Flat plates joined by joints.
    Plate,
    /// Stacked layers joined by shafts.
    Stacked,
    /// Primitives found by RANSAC made into plates and bent parts (textured, noisy models).
    Classifier,
    /// Every method; each result is written and the best by score is named.
    All,
}

impl MethodArg {
    /// The library's methods, in the order they run.
    pub fn methods(self) -> Vec<MethodKind> {
        match self {
            MethodArg::Plate => vec![MethodKind::Plate],
            MethodArg::Stacked => vec![MethodKind::Stacked],
            MethodArg::Classifier => vec![MethodKind::Classifier],
            MethodArg::All => MethodKind::ALL.to_vec(),
        }
    }
}

/// The joint type.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum JointArg {
    /// Finger (box) joints.
    Finger,
    /// The thesis' jim joints.
    Jim,
    /// Dovetails.
    Dovetail,
    /// Chosen per edge from the material and the angle.
    Auto,
}

/// Which labels are engraved.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum LabelsArg {
    /// Part numbers and connection numbers next to every jointed edge.
    Edges,
    /// Part numbers only.
    Parts,
    /// Nothing (saves laser time).
    None,
}

impl LabelsArg {
    /// The library's label mode.
    pub fn mode(self) -> LabelMode {
        match self {
            LabelsArg::Edges => LabelMode::Edges,
            LabelsArg::Parts => LabelMode::Parts,
            LabelsArg::None => LabelMode::None,
        }
    }
}

fn parse_bend(s: &str) -> Result<platener::Bending, String> {
    s.parse::<platener::Bending>().map_err(|e| e.to_string())
}

fn parse_sheet(s: &str) -> Result<SheetSize, String> {
    s.parse::<SheetSize>().map_err(|e| e.to_string())
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
    /// The sheet material; sets the default kerf.
    #[arg(short = 'm', long, value_enum, default_value = "wood")]
    pub material: MaterialArg,
    /// Which methods to run; `all` writes every result and names the best by score.
    #[arg(long, value_enum, default_value = "all")]
    pub method: MethodArg,
    /// Kerf in mm (default: the material's; `platener test-strip` measures yours).
    #[arg(long, value_name = "MM")]
    pub kerf: Option<f64>,
    /// Sheet size in mm as WxH (e.g. 600x400), or `fit` for one sheet per thickness just large
    /// enough.
    #[arg(long, value_name = "WxH|fit", default_value = "600x400", value_parser = parse_sheet)]
    pub sheet: SheetSize,
    /// Joint type: `auto` takes finger joints for wood and acrylic, JimJoints (snapping) for
    /// cardboard and paper.
    #[arg(long, value_enum, default_value = "auto")]
    pub joint: JointArg,
    /// Stacked method: the axis the layers are stacked along (`auto`: the model's largest flat
    /// face is laid flat).
    #[arg(long, value_name = "x|y|z|auto", default_value = "auto")]
    pub axis: String,
    /// Which labels to engrave.
    #[arg(long, value_enum, default_value = "edges")]
    pub labels: LabelsArg,
    /// Plate method: how plates that meet at an edge become one bent part instead of two
    /// jointed ones. `living-hinge`: rows of slits that let wood flex; `perforation`: dashed
    /// cuts, for cardboard; `score`: an engraved line to fold paper along; `heat`: an engraved
    /// line to bend acrylic along over a heater; `none`: no bends, joints everywhere; `auto`
    /// (default): chosen by the material (wood → living hinge, cardboard → perforation, paper
    /// → score, acrylic → heat).
    #[arg(
        long,
        value_name = "auto|none|living-hinge|perforation|score|heat",
        default_value = "auto",
        value_parser = parse_bend
    )]
    pub bend: platener::Bending,
    /// Skip (and list) model files larger than this many MB (10^6 bytes).
    #[arg(long, value_name = "MB", value_parser = parse_non_negative)]
    pub max_filesize: Option<f64>,
    /// Models converted at the same time (default: one per core).
    #[arg(short = 'j', long, value_name = "N", value_parser = parse_jobs)]
    pub jobs: Option<usize>,
    /// Give up a model after this many seconds (all its methods together); 0: never.
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
    /// Model options.
    #[command(flatten)]
    pub model_args: ModelArgs,
}

#[cfg(test)]
mod tests {
    use clap::Parser as _;
    use platener::Bending;
    use platener::plan::BendStyle;

    use super::{Cli, Command};

    fn bend_of(extra: &[&str]) -> Result<Bending, clap::Error> {
        let args = ["platener", "convert", "m.stl", "-o", "out"].iter().chain(extra);
        match Cli::try_parse_from(args)?.command {
            Command::Convert(c) => Ok(c.bend),
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

    #[test]
    fn bend_reaches_the_library_settings() {
        let Command::Convert(c) = Cli::try_parse_from(["platener", "convert", "m.stl", "-o", "o", "--bend", "score"])
            .expect("valid")
            .command
        else {
            panic!("not convert")
        };
        let settings = crate::convert::settings(&c).expect("valid settings");
        assert_eq!(settings.bending, Bending::Style(BendStyle::Score));
    }
}
