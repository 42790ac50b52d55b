//! The table of settings: one entry per setting, in the order forms and `--help` show them.

use serde_json::{Value, json};

use super::{Choice, Chosen, Def, Group, Kind};
use crate::joints::JointStyle;
use crate::method::MethodKind;
use crate::plan::laser::parse_laser;
use crate::plan::stock::parse_stock;
use crate::plan::{
    ColorProfile, Fit, LabelMode, Laser, MAX_KERF, MAX_MARGIN, Material, MeasuredThickness, NestEffort, SPACING_RANGE,
    SheetSize, StockSheet,
};
use crate::settings::{
    Bending, Features, MAX_SHEET_SIDE, MAX_THICKNESS, MAX_THICKNESSES, MAX_WELD, MIN_THICKNESS, PlateMode, SCALE_RANGE,
    SLICE_SPACING_RANGE, StackAxis, Units, Weld,
};

type SetResult = Result<(), String>;

/// Every setting, in the order a form shows them within their groups.
pub static DEFS: &[Def] = &[
    Def {
        name: "material",
        key: "material",
        short: Some('m'),
        label: "Material",
        group: Group::Material,
        kind: Kind::Choice { choices: MATERIALS },
        help: "The sheet material; it sets the default kerf, joint and bend style.",
        doc: "Wood (plywood, MDF) and acrylic get straight finger joints, cardboard and paper snapping \
              JimJoints; bends are living hinges in wood, perforations in cardboard, scores in paper and \
              heat lines in acrylic.",
        set: set_material,
        get: |c| json!(c.settings.cut.material.name()),
    },
    Def {
        name: "thickness",
        key: "thicknesses",
        short: Some('t'),
        label: "Sheet thickness",
        group: Group::Material,
        kind: Kind::Numbers {
            unit: "mm",
            min: MIN_THICKNESS,
            max: MAX_THICKNESS,
            max_count: MAX_THICKNESSES,
            common: &[1.0, 1.5, 2.0, 3.0, 4.0, 5.0, 6.0],
        },
        help: "The thicknesses of the sheets you have, mm; give several to let each plate take the one that fits.",
        doc: "A plate of the model becomes a part of the sheet closest to its wall thickness; the stacked \
              method's layers take the thinnest. Sheets are rarely what they are sold as (3 mm plywood \
              measures 2.6–3.4 mm): give the measured thickness after an @ (3@2.85) and slots and fingers \
              are cut for it, while files still name the sheet 3 mm.",
        set: set_thicknesses,
        get: get_thicknesses,
    },
    Def {
        name: "kerf",
        key: "kerf",
        short: None,
        label: "Kerf",
        group: Group::Material,
        kind: Kind::Number {
            unit: "mm",
            min: 0.0,
            max: MAX_KERF,
            auto: Some("the material's: wood 0.2, acrylic 0.15, cardboard 0.3, paper 0.1 mm"),
        },
        help: "The width the laser burns away, mm; measure yours with the kerf test strip.",
        doc: "Every outline is offset by half the kerf so parts come out at their true size and joints fit.",
        set: |c, v| {
            c.settings.cut.kerf = auto_number(v)?;
            Ok(())
        },
        get: |c| json!(c.settings.cut.kerf),
    },
    Def {
        name: "laser",
        key: "laser",
        short: None,
        label: "Laser",
        group: Group::Material,
        kind: Kind::Text {
            example: "co2, cut=12",
            shape: "KIND[,cut=MM/S,...]",
            format: "co2, co2-100w, k40, diode-10w or diode-20w, then any of cut=, engrave=, travel= (mm/s), \
                     pierce= (s), cut-power=, engrave-power= (%)",
        },
        help: "Your laser cutter (co2 is a 40–60 W tube; co2-100w, k40, diode-10w, diode-20w), and any speed \
               or power you know better: cut=12, engrave=150, travel=300 mm/s, pierce=0.2 s, cut-power=70, \
               engrave-power=20 %.",
        doc: "It sets the speeds of the time estimate and the LightBurn project, per material and \
              thickness from a table of published starting settings, and the project's powers, per \
              material (docs/cutting-plans.md); a speed or power you give holds for every sheet. The \
              plan itself does not change.",
        set: |c, v| {
            let text = v.join(",");
            c.settings.cut.laser = if text.trim().eq_ignore_ascii_case("none") {
                Laser::default()
            } else {
                parse_laser(&text)?
            };
            Ok(())
        },
        get: |c| json!(c.settings.cut.laser.text()),
    },
    Def {
        name: "units",
        key: "units",
        short: None,
        label: "Units",
        group: Group::Model,
        kind: Kind::Choice { choices: UNITS },
        help: "The unit of the model file's numbers (STL files do not say).",
        doc: "Most 3D-print models are in millimetres; models from CAD tools in inches or centimetres come \
              out 25.4 or 10 times too small without this.",
        set: set_units,
        get: |c| json!(units_name(c.settings.units)),
    },
    Def {
        name: "scale",
        key: "scale",
        short: None,
        label: "Scale",
        group: Group::Model,
        kind: Kind::Number {
            unit: "×",
            min: SCALE_RANGE.0,
            max: SCALE_RANGE.1,
            auto: None,
        },
        help: "A factor the model is scaled by after its unit.",
        doc: "Scale a model up when its walls are thinner than your sheets or its parts too small to cut, \
              down when it does not fit your sheets.",
        set: |c, v| {
            c.settings.scale = number(one(v)?)?;
            Ok(())
        },
        get: |c| json!(c.settings.scale),
    },
    Def {
        name: "sheet",
        key: "sheet",
        short: None,
        label: "Sheet size",
        group: Group::Sheets,
        kind: Kind::Sheet {
            presets: SHEETS,
            max: MAX_SHEET_SIDE,
        },
        help: "The sheet size, width × height in mm (e.g. 600x400), or fit for one sheet per thickness just large enough.",
        doc: "Parts are nested on as many sheets of this size as they need; a part larger than the sheet \
              within its margins is refused. For several sizes (a small sheet for the leftovers, offcuts, \
              a counted number of sheets), list them in Sheets in stock.",
        set: |c, v| {
            c.settings.cut.sheet = one(v)?
                .parse::<SheetSize>()
                .map_err(|_| "must be width x height in mm (e.g. 600x400) or fit".to_string())?;
            Ok(())
        },
        get: |c| json!(sheet_name(c.settings.cut.sheet)),
    },
    Def {
        name: "stock",
        key: "stock",
        short: None,
        label: "Sheets in stock",
        group: Group::Sheets,
        kind: Kind::Text {
            example: "3:600x400x2, 3:300x200",
            shape: "T:WxH[xN],...",
            format: "thickness:widthxheight[xcount] in mm, separated by commas, or none",
        },
        help: "The sheets you have: thickness, size and count of each (3:600x400x2, 6:300x200x1); \
               leave the count out for as many as needed.",
        doc: "Parts of each thickness are nested onto its sheets in the order listed, so offcuts listed \
              first are used first; the last sheet of a size listed without a count moves to a smaller \
              listed size when that holds its parts (3:600x400, 3:300x200 cuts the leftovers from a small \
              sheet); a plan that needs more sheets than listed is refused, naming the parts left over. \
              Thicknesses not listed go on sheets of the sheet size.",
        set: |c, v| {
            let text = v.join(",");
            c.settings.cut.stock = if text.trim().eq_ignore_ascii_case("none") {
                Vec::new()
            } else {
                parse_stock(&text, MAX_SHEET_SIDE)?
            };
            Ok(())
        },
        get: |c| {
            let listed: Vec<String> = c.settings.cut.stock.iter().map(StockSheet::text).collect();
            json!(if listed.is_empty() {
                "none".to_string()
            } else {
                listed.join(",")
            })
        },
    },
    Def {
        name: "margin",
        key: "margin",
        short: None,
        label: "Margin",
        group: Group::Sheets,
        kind: Kind::Number {
            unit: "mm",
            min: 0.0,
            max: MAX_MARGIN,
            auto: None,
        },
        help: "Free border between the sheet's edge and any part, mm (clamps, a rough or burnt edge).",
        doc: "No cut path comes nearer the sheet's edge than this; a part larger than the sheet within its \
              margins is refused.",
        set: |c, v| {
            c.settings.cut.margin = number(one(v)?)?;
            Ok(())
        },
        get: |c| json!(c.settings.cut.margin),
    },
    Def {
        name: "spacing",
        key: "spacing",
        short: None,
        label: "Spacing",
        group: Group::Sheets,
        kind: Kind::Number {
            unit: "mm",
            min: SPACING_RANGE.0,
            max: SPACING_RANGE.1,
            auto: None,
        },
        help: "Least distance between the cut paths of two parts, mm; more than the kerf.",
        doc: "Closer parts save material; a little more keeps a thin web between them from burning through \
              or warping in brittle acrylic.",
        set: |c, v| {
            c.settings.cut.spacing = number(one(v)?)?;
            Ok(())
        },
        get: |c| json!(c.settings.cut.spacing),
    },
    Def {
        name: "joint",
        key: "joint",
        short: None,
        label: "Joint",
        group: Group::Joints,
        kind: Kind::Choice { choices: JOINTS },
        help: "The joint between plates; auto takes finger joints for wood and acrylic, JimJoints for cardboard and paper.",
        doc: "Finger joints are exact negatives of each other; JimJoints widen towards the tip and snap \
              behind the other part; dovetails are wedged by small keys cut from the same sheet.",
        set: set_joint,
        get: |c| json!(c.settings.joints.style.map_or("auto", joint_name)),
    },
    Def {
        name: "nesting",
        key: "nesting",
        short: None,
        label: "Nesting",
        group: Group::Sheets,
        kind: Kind::Choice { choices: NESTINGS },
        help: "How long nesting searches for a denser layout: fast, good or best.",
        doc: "Nesting lays the parts out in several orders side by side and keeps the densest: fast tries \
              one (a plan at once), good eight, best forty-eight (for the sheets you buy; several times \
              as long as good, some ten seconds on a large plan). Good and best then shorten the last sheet: they push the parts at its end \
              onto the others and move the parts that overlap until none does, again and again.",
        set: |c, v| {
            c.settings.cut.nest_tries = named(v, NestEffort::ALL, NestEffort::name, NESTINGS)?.tries();
            Ok(())
        },
        get: |c| json!(NestEffort::of(c.settings.cut.nest_tries).name()),
    },
    Def {
        name: "colors",
        key: "colors",
        short: None,
        label: "Line colours",
        group: Group::Sheets,
        kind: Kind::Choice { choices: COLORS },
        help: "The SVG sheets' line colours and widths per operation, as your laser software expects them.",
        doc: "Laser programs tell cutting from engraving by colour. Each profile gives text, score lines, \
              inner cuts (holes, slits) and outlines the colours its program maps to its own operations; \
              the DXF and LightBurn files name their layers and do not change.",
        set: |c, v| {
            c.settings.cut.colors = named(v, ColorProfile::ALL, ColorProfile::name, COLORS)?;
            Ok(())
        },
        get: |c| json!(c.settings.cut.colors.name()),
    },
    Def {
        name: "reference-square",
        key: "reference_square",
        short: None,
        label: "Reference square",
        group: Group::Sheets,
        kind: Kind::Choice { choices: YES_NO },
        help: "Score a 100 mm square on each sheet, beside the parts, to check the scale after import.",
        doc: "A laser program that imports a file at the wrong scale shows the square at another size: \
              measure it before cutting. Sheets without room beside the parts get none.",
        set: |c, v| {
            c.settings.cut.reference_square = yes(v)?;
            Ok(())
        },
        get: |c| json!(yes_no(c.settings.cut.reference_square)),
    },
    Def {
        name: "fit",
        key: "fit",
        short: None,
        label: "Fit",
        group: Group::Joints,
        kind: Kind::Choice { choices: FITS },
        help: "How tight joints fit: press (0.1 mm interference), snug (exact) or loose (0.15 mm play).",
        doc: "A clearance across each finger and tab, both flanks together, on top of the kerf: every cut \
              path moves out by a quarter of it for press (in for loose). Press fits hold without glue when \
              tapped home; loose fits slide together by hand. Measure your sheet's fit with the slot row of \
              the kerf test strip.",
        set: |c, v| {
            c.settings.cut.fit = named(v, Fit::ALL, Fit::name, FITS)?;
            Ok(())
        },
        get: |c| json!(c.settings.cut.fit.name()),
    },
    Def {
        name: "crush-ribs",
        key: "crush_ribs",
        short: None,
        label: "Crush ribs",
        group: Group::Joints,
        kind: Kind::Choice { choices: YES_NO },
        help: "Small bumps on the walls of each slot a tab goes through, which crush as the tab is pressed in.",
        doc: "For press fits in plywood or MDF whose thickness varies: each slot wall gets one rib (two in \
              slots from 20 mm long), 0.25 mm high on a 1.5 mm foot, and the slot keeps its width, so a tab \
              a little thicker than sold still goes in and a thinner one is still held. Not for acrylic, \
              which cracks instead of crushing; use with the snug fit.",
        set: |c, v| {
            c.settings.cut.crush_ribs = yes(v)?;
            Ok(())
        },
        get: |c| json!(yes_no(c.settings.cut.crush_ribs)),
    },
    Def {
        name: "labels",
        key: "labels",
        short: None,
        label: "Labels",
        group: Group::Joints,
        kind: Kind::Choice { choices: LABELS },
        help: "What is engraved on the parts: part and edge numbers, part numbers, or nothing.",
        doc: "Edge numbers say which edges join (the same number on both); engraving costs laser time.",
        set: set_labels,
        get: |c| json!(labels_name(c.settings.cut.labels)),
    },
    Def {
        name: "bend",
        key: "bend",
        short: None,
        label: "Bends",
        group: Group::Joints,
        kind: Kind::Choice { choices: BENDS },
        help: "How plates meeting at a shallow edge become one bent part; auto takes the material's style.",
        doc: "Living hinges (rows of slits) flex wood, perforations fold cardboard, scores fold paper and \
              heat lines mark where acrylic is bent over a heater; none keeps every plate its own part.",
        set: |c, v| {
            c.settings.bending = one(v)?.parse::<Bending>().map_err(|_| choices_message(BENDS))?;
            Ok(())
        },
        get: |c| json!(bending_name(c.settings.bending)),
    },
    Def {
        name: "features",
        key: "features",
        short: None,
        label: "Features on plates",
        group: Group::Joints,
        kind: Kind::Choice { choices: FEATURES },
        help: "Text, pockets and bosses on one face of a plate: engraved, cut through, or left out.",
        doc: "Features that do not go through a plate cannot be cut; engraving draws them as score marks \
              on the face where they are.",
        set: |c, v| {
            c.settings.features = one(v)?.parse::<Features>().map_err(|_| choices_message(FEATURES))?;
            Ok(())
        },
        get: |c| json!(features_name(c.settings.features)),
    },
    Def {
        name: "method",
        key: "method",
        short: None,
        label: "Method",
        group: Group::Method,
        kind: Kind::Choice { choices: METHODS },
        help: "How the model is made from sheets; all tries every method side by side and names the best.",
        doc: "Plates suit boxes and enclosures, stacked layers suit organic shapes, the classifier suits \
              textured or noisy models of plates.",
        set: set_method,
        get: |c| json!(method_name(&c.methods)),
    },
    Def {
        name: "axis",
        key: "axis",
        short: None,
        label: "Stacking axis",
        group: Group::Method,
        kind: Kind::Choice { choices: AXES },
        help: "The stacked method's slicing direction; auto lays the model's largest flat face flat.",
        doc: "Layers stacked along z are the model as it would be 3D-printed.",
        set: |c, v| {
            c.settings.stacked.axis = one(v)?.parse::<StackAxis>().map_err(|_| choices_message(AXES))?;
            Ok(())
        },
        get: |c| json!(axis_name(c.settings.stacked.axis)),
    },
    Def {
        name: "slice-spacing",
        key: "slice_spacing",
        short: None,
        label: "Slice spacing",
        group: Group::Method,
        kind: Kind::Number {
            unit: "mm",
            min: SLICE_SPACING_RANGE.0,
            max: SLICE_SPACING_RANGE.1,
            auto: Some("about ten slices along the longest side, at least three sheet thicknesses apart"),
        },
        help: "The interlocked method's distance between neighbouring slices, mm.",
        doc: "Closer slices follow the model's shape more closely and reach thin parts (legs, a tail), \
              at the cost of more parts and slots.",
        set: |c, v| {
            c.settings.interlocked.spacing = auto_number(v)?;
            Ok(())
        },
        get: |c| json!(c.settings.interlocked.spacing),
    },
    Def {
        name: "weld",
        key: "weld",
        short: None,
        label: "Weld distance",
        group: Group::Advanced,
        kind: Kind::Number {
            unit: "mm",
            min: 0.0,
            max: MAX_WELD,
            auto: Some("from the model's size, at most 2 mm"),
        },
        help: "Vertices closer than this are merged before plates are found; 0 merges exact duplicates only.",
        doc: "Welding removes the bevels and tiny steps editors leave, so faces that should be one plane \
              are; a distance near a wall's thickness would fuse the wall's faces.",
        set: set_weld,
        get: |c| match c.settings.weld {
            Weld::Auto => Value::Null,
            Weld::Off => json!(0.0),
            Weld::Distance(d) => json!(d),
        },
    },
    Def {
        name: "plates",
        key: "plates",
        short: None,
        label: "Plates",
        group: Group::Advanced,
        kind: Kind::Choice { choices: PLATES },
        help: "Which plates the plate method looks for: pairs of faces a sheet apart, and leftover faces made into plates.",
        doc: "Inherent plates only keeps a solid block from becoming a hull of extruded plates.",
        set: |c, v| {
            c.settings.plates.mode = match one(v)? {
                "all" => PlateMode::InherentAndExtruded,
                "inherent" => PlateMode::InherentOnly,
                _ => return Err(choices_message(PLATES)),
            };
            Ok(())
        },
        get: |c| {
            json!(match c.settings.plates.mode {
                PlateMode::InherentAndExtruded => "all",
                PlateMode::InherentOnly => "inherent",
            })
        },
    },
];

const MATERIALS: &[Choice] = &[
    Choice {
        value: "wood",
        label: "Wood",
        help: "Plywood, MDF, solid wood (kerf 0.2 mm).",
    },
    Choice {
        value: "acrylic",
        label: "Acrylic",
        help: "Cast or extruded acrylic (kerf 0.15 mm).",
    },
    Choice {
        value: "cardboard",
        label: "Cardboard",
        help: "Corrugated or grey cardboard (kerf 0.3 mm).",
    },
    Choice {
        value: "paper",
        label: "Paper",
        help: "Paper and thin card (kerf 0.1 mm).",
    },
];

const UNITS: &[Choice] = &[
    Choice {
        value: "mm",
        label: "Millimetres",
        help: "The file's numbers are millimetres (most 3D-print models).",
    },
    Choice {
        value: "cm",
        label: "Centimetres",
        help: "The file's numbers are centimetres.",
    },
    Choice {
        value: "in",
        label: "Inches",
        help: "The file's numbers are inches.",
    },
];

const SHEETS: &[Choice] = &[
    Choice {
        value: "600x400",
        label: "600 × 400 mm",
        help: "The bed of common 60 W desktop CO₂ lasers.",
    },
    Choice {
        value: "495x279",
        label: "Glowforge 495 × 279 mm",
        help: "The Glowforge's cutting area.",
    },
    Choice {
        value: "600x308",
        label: "xTool P2 600 × 308 mm",
        help: "The xTool P2's cutting area.",
    },
    Choice {
        value: "300x200",
        label: "K40 300 × 200 mm",
        help: "The K40's cutting area.",
    },
    Choice {
        value: "2440x1220",
        label: "Board 2440 × 1220 mm",
        help: "A full 8 × 4 ft board, for a large-format laser.",
    },
    Choice {
        value: "fit",
        label: "Fit",
        help: "One sheet per thickness, just large enough for its parts.",
    },
];

const JOINTS: &[Choice] = &[
    Choice {
        value: "auto",
        label: "Auto",
        help: "By material: finger joints for wood and acrylic, JimJoints for cardboard and paper.",
    },
    Choice {
        value: "finger",
        label: "Finger",
        help: "Straight fingers, exact negatives of each other.",
    },
    Choice {
        value: "jim",
        label: "JimJoint",
        help: "Fingers that widen towards the tip and snap behind the other part.",
    },
    Choice {
        value: "dovetail",
        label: "Dovetail",
        help: "Dovetails wedged tight by small keys.",
    },
];

const NESTINGS: &[Choice] = &[
    Choice {
        value: "fast",
        label: "Fast",
        help: "One order, largest part first: a plan at once.",
    },
    Choice {
        value: "good",
        label: "Good",
        help: "Eight orders, the densest kept, its last sheet shortened.",
    },
    Choice {
        value: "best",
        label: "Best",
        help: "Forty-eight orders, the four densest shortened: denser, several times as long.",
    },
];

const FITS: &[Choice] = &[
    Choice {
        value: "press",
        label: "Press",
        help: "0.1 mm interference: tap the joints home; they hold without glue.",
    },
    Choice {
        value: "snug",
        label: "Snug",
        help: "Parts at their exact size: joints go together firmly by hand.",
    },
    Choice {
        value: "loose",
        label: "Loose",
        help: "0.15 mm play: joints slide together, for glue or for taking apart.",
    },
];

const COLORS: &[Choice] = &[
    Choice {
        value: "classic",
        label: "Classic",
        help: "Red hairline cuts, blue hairline engraving: what most laser software reads as cut and engrave.",
    },
    Choice {
        value: "lightburn",
        label: "LightBurn",
        help: "LightBurn's own palette colours, one layer per operation: text black, scores blue, holes green, outlines red.",
    },
    Choice {
        value: "glowforge",
        label: "Glowforge",
        help: "One pure colour per operation, in the order they should run: text black, scores blue, holes green, outlines red.",
    },
    Choice {
        value: "xtool",
        label: "xTool",
        help: "As Glowforge: xTool Creative Space makes one layer per colour.",
    },
    Choice {
        value: "ponoko",
        label: "Ponoko",
        help: "Ponoko's convention: blue cuts, red engraving, 0.01 mm lines.",
    },
];

const YES_NO: &[Choice] = &[
    Choice {
        value: "no",
        label: "No",
        help: "Nothing but the parts on the sheets.",
    },
    Choice {
        value: "yes",
        label: "Yes",
        help: "A scored 100 mm square with \"100 MM\" in it, beside the parts.",
    },
];

const LABELS: &[Choice] = &[
    Choice {
        value: "edges",
        label: "Parts and edges",
        help: "Part numbers, and the connection number next to every jointed edge.",
    },
    Choice {
        value: "parts",
        label: "Parts only",
        help: "Part numbers only.",
    },
    Choice {
        value: "none",
        label: "None",
        help: "Nothing engraved (saves laser time).",
    },
];

const BENDS: &[Choice] = &[
    Choice {
        value: "auto",
        label: "Auto",
        help: "The material's style: living hinge, perforation, score or heat line.",
    },
    Choice {
        value: "none",
        label: "None",
        help: "No bent parts: joints everywhere.",
    },
    Choice {
        value: "living-hinge",
        label: "Living hinge",
        help: "Rows of slits that let wood flex.",
    },
    Choice {
        value: "perforation",
        label: "Perforation",
        help: "Dashed cuts to fold cardboard along.",
    },
    Choice {
        value: "score",
        label: "Score",
        help: "An engraved line to fold paper along.",
    },
    Choice {
        value: "heat",
        label: "Heat line",
        help: "An engraved line to bend acrylic along over a heater.",
    },
];

const FEATURES: &[Choice] = &[
    Choice {
        value: "engrave",
        label: "Engrave",
        help: "Scored on the face where they are.",
    },
    Choice {
        value: "cut",
        label: "Cut through",
        help: "Every hole of a plate's faces is cut through.",
    },
    Choice {
        value: "ignore",
        label: "Ignore",
        help: "Left out: plain plates.",
    },
];

const METHODS: &[Choice] = &[
    Choice {
        value: "all",
        label: "Best of all",
        help: "Every method side by side; the best by score is named.",
    },
    Choice {
        value: "plate",
        label: "Plates",
        help: "Flat plates joined by joints.",
    },
    Choice {
        value: "stacked",
        label: "Stacked layers",
        help: "Layers joined by shafts.",
    },
    Choice {
        value: "classifier",
        label: "Classifier",
        help: "Primitives found in textured or noisy models, made into plates and bent parts.",
    },
    Choice {
        value: "interlocked",
        label: "Interlocked slices",
        help: "Upright slices crossing in halved slots, held without glue.",
    },
];

const AXES: &[Choice] = &[
    Choice {
        value: "auto",
        label: "Auto",
        help: "The model's largest flat face is laid flat.",
    },
    Choice {
        value: "x",
        label: "x",
        help: "Layers stacked along the model's x axis.",
    },
    Choice {
        value: "y",
        label: "y",
        help: "Layers stacked along the model's y axis.",
    },
    Choice {
        value: "z",
        label: "z",
        help: "Layers stacked along z, as the model would be printed.",
    },
];

const PLATES: &[Choice] = &[
    Choice {
        value: "all",
        label: "All",
        help: "Inherent plates, then leftover faces extruded into plates.",
    },
    Choice {
        value: "inherent",
        label: "Inherent only",
        help: "Only pairs of faces a sheet thickness apart.",
    },
];

/// The one value of a single-valued setting.
fn one<'a>(values: &[&'a str]) -> Result<&'a str, String> {
    match values {
        [v] => Ok(v.trim()),
        [] => Err("needs a value".into()),
        _ => Err("takes one value".into()),
    }
}

/// A yes or no setting's value.
fn yes(values: &[&str]) -> Result<bool, String> {
    match one(values)? {
        "yes" => Ok(true),
        "no" => Ok(false),
        _ => Err(choices_message(YES_NO)),
    }
}

/// How a yes or no setting reads.
fn yes_no(on: bool) -> &'static str {
    if on { "yes" } else { "no" }
}

/// A number; ranges are [`crate::Settings::validate`]'s, which names them.
fn number(text: &str) -> Result<f64, String> {
    match text.trim().parse::<f64>() {
        Ok(v) if v.is_finite() => Ok(v),
        _ => Err("takes a number".into()),
    }
}

/// The one value of `all` whose name is the one value in `v` (a choice's enum).
fn named<T: Copy, const N: usize>(
    v: &[&str],
    all: [T; N],
    name: fn(T) -> &'static str,
    choices: &[Choice],
) -> Result<T, String> {
    let text = one(v)?;
    all.into_iter()
        .find(|&x| name(x) == text)
        .ok_or_else(|| choices_message(choices))
}

/// "must be one of a, b, c".
fn choices_message(choices: &[Choice]) -> String {
    let values: Vec<&str> = choices.iter().map(|c| c.value).collect();
    format!("must be one of {}", values.join(", "))
}

/// The choice's value that `text` names, ignoring case and spaces around it.
fn pick<'a>(text: &str, choices: &'a [Choice]) -> Result<&'a str, String> {
    let text = text.trim();
    choices
        .iter()
        .find(|c| c.value.eq_ignore_ascii_case(text))
        .map(|c| c.value)
        .ok_or_else(|| choices_message(choices))
}

/// `auto` (or an empty field) leaves a number to platener.
fn is_auto(text: &str) -> bool {
    let t = text.trim();
    t.is_empty() || t.eq_ignore_ascii_case("auto")
}

/// `None` for `auto`, else the number (its range is checked by `validate`).
fn auto_number(values: &[&str]) -> Result<Option<f64>, String> {
    let text = one(values)?;
    if is_auto(text) {
        Ok(None)
    } else {
        number(text).map(Some)
    }
}

fn set_material(c: &mut Chosen, v: &[&str]) -> SetResult {
    c.settings.cut.material = match pick(one(v)?, MATERIALS)? {
        "acrylic" => Material::Acrylic,
        "cardboard" => Material::Cardboard,
        "paper" => Material::Paper,
        _ => Material::Wood,
    };
    Ok(())
}

/// Thicknesses as numbers, or `nominal@measured` for a sheet that measures other than it is
/// sold as: the measured value is the sheet's thickness, the nominal one names it.
fn set_thicknesses(c: &mut Chosen, v: &[&str]) -> SetResult {
    if v.is_empty() {
        return Err("needs at least one thickness".into());
    }
    let mut thicknesses = Vec::with_capacity(v.len());
    let mut measured = Vec::new();
    for text in v {
        match MeasuredThickness::parse(text) {
            Some(m) => {
                let m = m?;
                thicknesses.push(m.measured);
                measured.push(m);
            }
            None => thicknesses.push(number(text)?),
        }
    }
    c.settings.thicknesses = thicknesses;
    c.settings.cut.measured = measured;
    Ok(())
}

/// The thicknesses as the API writes them: numbers, and `"3@2.85"` for measured sheets.
fn get_thicknesses(c: &Chosen) -> Value {
    let cut = &c.settings.cut;
    c.settings
        .thicknesses
        .iter()
        .map(|&t| cut.measured_as(t).map_or_else(|| json!(t), |m| json!(m.text())))
        .collect()
}

fn set_units(c: &mut Chosen, v: &[&str]) -> SetResult {
    c.settings.units = match pick(one(v)?, UNITS)? {
        "cm" => Units::Cm,
        "in" => Units::In,
        _ => Units::Mm,
    };
    Ok(())
}

fn set_joint(c: &mut Chosen, v: &[&str]) -> SetResult {
    c.settings.joints.style = match pick(one(v)?, JOINTS)? {
        "finger" => Some(JointStyle::Finger),
        "jim" => Some(JointStyle::Jim),
        "dovetail" => Some(JointStyle::Dovetail),
        _ => None,
    };
    Ok(())
}

fn set_labels(c: &mut Chosen, v: &[&str]) -> SetResult {
    c.settings.cut.labels = match pick(one(v)?, LABELS)? {
        "parts" => LabelMode::Parts,
        "none" => LabelMode::None,
        _ => LabelMode::Edges,
    };
    Ok(())
}

fn set_method(c: &mut Chosen, v: &[&str]) -> SetResult {
    c.methods = match pick(one(v)?, METHODS)? {
        "all" => MethodKind::ALL.to_vec(),
        name => vec![name.parse::<MethodKind>().map_err(|_| choices_message(METHODS))?],
    };
    Ok(())
}

fn set_weld(c: &mut Chosen, v: &[&str]) -> SetResult {
    c.settings.weld = match auto_number(v)? {
        None => Weld::Auto,
        Some(0.0) => Weld::Off,
        Some(d) => Weld::Distance(d),
    };
    Ok(())
}

fn units_name(u: Units) -> &'static str {
    match u {
        Units::Mm => "mm",
        Units::Cm => "cm",
        Units::In => "in",
    }
}

/// A sheet size as the `sheet` setting writes it.
pub fn sheet_name(sheet: SheetSize) -> String {
    match sheet {
        SheetSize::Fixed { width, height } => format!("{width}x{height}"),
        SheetSize::Fit => "fit".into(),
    }
}

fn joint_name(style: JointStyle) -> &'static str {
    match style {
        JointStyle::Finger => "finger",
        JointStyle::Jim => "jim",
        JointStyle::Dovetail => "dovetail",
    }
}

fn labels_name(labels: LabelMode) -> &'static str {
    match labels {
        LabelMode::Edges => "edges",
        LabelMode::Parts => "parts",
        LabelMode::None => "none",
    }
}

fn bending_name(bending: Bending) -> &'static str {
    match bending {
        Bending::Auto => "auto",
        Bending::None => "none",
        Bending::Style(style) => style.name(),
    }
}

fn features_name(features: Features) -> &'static str {
    match features {
        Features::Engrave => "engrave",
        Features::Cut => "cut",
        Features::Ignore => "ignore",
    }
}

fn method_name(methods: &[MethodKind]) -> &'static str {
    match methods {
        [one] => one.name(),
        _ => "all",
    }
}

fn axis_name(axis: StackAxis) -> &'static str {
    match axis {
        StackAxis::Auto => "auto",
        StackAxis::X => "x",
        StackAxis::Y => "y",
        StackAxis::Z => "z",
    }
}
