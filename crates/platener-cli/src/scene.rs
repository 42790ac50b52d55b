//! `platener scene`: converts a model through the library and writes one view as a GLB.

use anyhow::Context as _;
use platener::convert::{MethodResult, PanicHook, Request, convert_all, no_progress};
use platener::scene::View;
use platener::{Cancel, Source};

use crate::args::SceneArgs;
use crate::convert::UsageError;

/// Examples shown under `platener scene --help`.
pub const EXAMPLES: &str = "Examples:
  platener scene examples/box-3mm.stl -o box.glb
      the final assembly of the best method's parts
  platener scene examples/phone-stand.stl --view plates --method plate -o plates.glb
  platener scene model.stl --view coplanar -o groups.glb

Views: model (the mesh as read), wireframe (its edges), coplanar (each planar group its own
colour), primitives (each primitive the classifier found its own colour, its inlier samples
as points; --method classifier), plates (each plate a slab), bent (plates by bent part), final
(every part as cut, joints included). Lengths are mm under a 0.001 root scale, Z-up turned to
Y-up.";

/// Runs the command.
pub fn run(args: &SceneArgs) -> anyhow::Result<()> {
    let usage = |e: anyhow::Error| anyhow::Error::new(UsageError(e));
    let view: View = args.view.parse().map_err(|e| usage(anyhow::Error::new(e)))?;
    let chosen = args.settings.chosen().map_err(usage)?;
    let _hook = PanicHook::install();
    let request = Request {
        methods: chosen.methods,
        ..Request::new(Source::File(args.model.clone()), chosen.settings)
    };
    let all = convert_all(request, &Cancel::default(), no_progress());
    // The best method first, then the others in order: the first that reached this view.
    let mut order: Vec<&MethodResult> = all.best().into_iter().collect();
    order.extend(all.methods.iter().filter(|m| Some(m.method) != all.best));
    let mut why = Vec::new();
    let mut drawn = None;
    for m in order {
        let scene = match (&m.state, &m.error) {
            (Some(state), error) => state.scene(view).map_err(|e| match error {
                Some(failed) => format!("{e} ({failed})"),
                None => e.to_string(),
            }),
            (None, error) => Err(error.as_ref().map_or_else(|| "no result".into(), ToString::to_string)),
        };
        match scene {
            Ok(scene) => {
                drawn = Some((m.method, scene));
                break;
            }
            Err(e) => why.push(format!("{}: {e}", m.method.name())),
        }
    }
    let Some((method, scene)) = drawn else {
        anyhow::bail!(
            "no method could draw the {view} view of {}: {}",
            args.model.display(),
            why.join("; ")
        );
    };
    std::fs::write(&args.output, &scene.glb).with_context(|| format!("cannot write {}", args.output.display()))?;
    eprintln!(
        "{}: the {view} view of the {} method, {} nodes, {} triangles, {} lines, {} points, {} bytes",
        args.output.display(),
        method.name(),
        scene.nodes,
        scene.triangles,
        scene.lines,
        scene.points,
        scene.glb.len()
    );
    for note in &scene.notes {
        eprintln!("note: {note}");
    }
    Ok(())
}
