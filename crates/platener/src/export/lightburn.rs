//! LightBurn projects (`.lbrn2`, issue 34): the sheet as LightBurn opens it, one layer per
//! operation, so no colour has to be guessed into a layer.
//!
//! An SVG's colours reach LightBurn's layers by nearest palette colour, which makers report as
//! inconsistent; a project names its layers. Three layers, in the order LightBurn runs them
//! (their `priority`): **Engrave** (scores and numbers, blue), **Cut inner** (holes and slits,
//! green), **Cut outer** (outlines, red), so over the whole sheet everything is engraved
//! before anything is cut and every hole is cut before any outline frees a part. A fourth
//! layer, **Sheet**, holds the sheet's outline with its output off: a frame to place the
//! material by, never cut unless the maker turns it on. Shapes are
//! paths in mm, written in the file's cut order ([`super::order`]). LightBurn's y axis points
//! up: y is written as `height − y`, as in the DXF.
//!
//! Speeds are the `laser` setting's for the sheet (the time estimate's); powers are starting
//! points per material for a 40–60 W CO₂ laser ([`power`], docs/cutting-plans.md), to check
//! with the test strip before a whole sheet.

use std::fmt::Write as _;

use glam::DVec2;

use crate::draw::svg::{SvgGroup, num};
use crate::plan::{CutSettings, Material};

/// LightBurn's layer of an operation: its index (which also picks the layer's colour in
/// LightBurn's palette), name, and the order LightBurn runs it in.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Layer {
    /// The layer index: 1 blue, 2 red, 3 green in LightBurn's palette.
    pub index: u32,
    /// Its name in LightBurn's Cuts / Layers list.
    pub name: &'static str,
    /// Lower runs first.
    pub priority: u32,
}

/// Scores, labels and other engraving.
pub const ENGRAVE: Layer = Layer {
    index: 1,
    name: "Engrave",
    priority: 0,
};
/// Holes and slits.
pub const CUT_INNER: Layer = Layer {
    index: 3,
    name: "Cut inner",
    priority: 1,
};
/// Outlines.
pub const CUT_OUTER: Layer = Layer {
    index: 2,
    name: "Cut outer",
    priority: 2,
};
/// The sheet's outline, output off.
pub const SHEET: Layer = Layer {
    index: 0,
    name: "Sheet (not cut)",
    priority: 3,
};

/// Starting powers (per cent of the tube's maximum) for cutting and for engraving `material`
/// on a 40–60 W CO₂ laser at the plan's speeds; the `laser` setting's `cut-power` and
/// `engrave-power` take their place.
pub fn power(material: Material) -> (f64, f64) {
    match material {
        Material::Wood => (70.0, 20.0),
        Material::Acrylic => (65.0, 15.0),
        Material::Cardboard => (40.0, 12.0),
        Material::Paper => (20.0, 8.0),
    }
}

/// The LightBurn project of one sheet `width` × `height` mm holding `groups` (in cut order,
/// sheet coordinates with y down), `thickness` mm thick; `stock` says which sheet it is, in
/// the project's notes. Its layers' speeds are the `laser` setting's for the sheet.
pub fn sheet_lbrn2(
    (width, height, thickness): (f64, f64, f64),
    groups: &[SvgGroup],
    settings: &CutSettings,
    stock: &str,
) -> String {
    let (cut_power, engrave_power) = power(settings.material);
    let cut_power = settings.laser.cut_power.unwrap_or(cut_power);
    let engrave_power = settings.laser.engrave_power.unwrap_or(engrave_power);
    let speeds = settings.laser.speeds(settings.material, thickness);
    let mut s = String::new();
    s.push_str("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n");
    s.push_str("<LightBurnProject AppVersion=\"1.4.00\" FormatVersion=\"1\" MaterialHeight=\"0\" MirrorX=\"False\" MirrorY=\"False\">\n");
    for (layer, speed, power) in [
        (ENGRAVE, speeds.engrave, engrave_power),
        (CUT_INNER, speeds.cut, cut_power),
        (CUT_OUTER, speeds.cut, cut_power),
    ] {
        cut_setting(&mut s, layer, speed, power, true);
    }
    cut_setting(&mut s, SHEET, speeds.cut, 0.0, false);
    let flip = |points: &[DVec2]| -> Vec<DVec2> { points.iter().map(|p| DVec2::new(p.x, height - p.y)).collect() };
    let sheet = [
        DVec2::ZERO,
        DVec2::new(width, 0.0),
        DVec2::new(width, height),
        DVec2::new(0.0, height),
    ];
    shape(&mut s, SHEET, &flip(&sheet), true);
    for g in groups {
        for line in g.engrave.iter().map(|e| &e.path) {
            shape(&mut s, ENGRAVE, &flip(line), false);
        }
        for slit in &g.slits {
            shape(&mut s, CUT_INNER, &flip(slit), false);
        }
        // The rings are in cut order: holes first, the outline last.
        let last = g.cut.len().saturating_sub(1);
        for (k, ring) in g.cut.iter().enumerate() {
            let layer = if k == last { CUT_OUTER } else { CUT_INNER };
            shape(&mut s, layer, &flip(ring), true);
        }
    }
    let _ = writeln!(
        s,
        "    <Notes ShowOnLoad=\"0\" Notes=\"{}\"/>",
        crate::draw::svg::xml_escape(stock)
    );
    s.push_str("</LightBurnProject>\n");
    s
}

/// One layer's settings: a vector (Line) operation at `speed` mm/s and `power` per cent, sent
/// to the laser only when `output`.
fn cut_setting(s: &mut String, layer: Layer, speed: f64, power: f64, output: bool) {
    let _ = write!(
        s,
        "    <CutSetting type=\"Cut\">\n        <index Value=\"{}\"/>\n        <name Value=\"{}\"/>\n        \
         <minPower Value=\"{p}\"/>\n        <maxPower Value=\"{p}\"/>\n        <speed Value=\"{}\"/>\n        \
         <numPasses Value=\"1\"/>\n        <priority Value=\"{}\"/>\n        <doOutput Value=\"{}\"/>\n    </CutSetting>\n",
        layer.index,
        layer.name,
        num(speed),
        layer.priority,
        u8::from(output),
        p = num(power),
    );
}

/// One path shape: its vertices and the lines between them (closing back to the first when
/// `closed`).
fn shape(s: &mut String, layer: Layer, points: &[DVec2], closed: bool) {
    if points.len() < 2 {
        return;
    }
    let _ = write!(
        s,
        "    <Shape Type=\"Path\" CutIndex=\"{}\">\n        <XForm>1 0 0 1 0 0</XForm>\n        <VertList>",
        layer.index
    );
    for p in points {
        let _ = write!(s, "V{} {}", num(p.x), num(p.y));
    }
    s.push_str("</VertList>\n        <PrimList>");
    let n = points.len();
    let segments = if closed { n } else { n - 1 };
    for i in 0..segments {
        let _ = write!(s, "L{} {}", i, (i + 1) % n);
    }
    s.push_str("</PrimList>\n    </Shape>\n");
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_sheet_has_three_layers_and_its_paths_in_order() {
        let g = SvgGroup {
            id: "part-1".into(),
            cut: vec![
                vec![
                    DVec2::new(4.0, 4.0),
                    DVec2::new(4.0, 6.0),
                    DVec2::new(6.0, 6.0),
                    DVec2::new(6.0, 4.0),
                ],
                vec![
                    DVec2::new(1.0, 1.0),
                    DVec2::new(11.0, 1.0),
                    DVec2::new(11.0, 9.0),
                    DVec2::new(1.0, 9.0),
                ],
            ],
            slits: vec![vec![DVec2::new(8.0, 2.0), DVec2::new(8.0, 5.0)]],
            engrave: vec![crate::draw::svg::Engraved::score(vec![
                DVec2::new(2.0, 2.0),
                DVec2::new(3.0, 3.0),
            ])],
        };
        let text = sheet_lbrn2(
            (200.0, 100.0, 3.0),
            std::slice::from_ref(&g),
            &CutSettings::default(),
            "a <b> & c",
        );
        let cut_indices: Vec<&str> = text
            .match_indices("CutIndex=\"")
            .map(|(at, m)| &text[at + m.len()..at + m.len() + 1])
            .collect();
        assert_eq!(
            cut_indices,
            ["0", "1", "3", "3", "2"],
            "sheet, engrave, slit, hole, outline"
        );
        assert!(
            text.contains("<VertList>V0 100V200 100V200 0V0 0</VertList>"),
            "the sheet"
        );
        assert_eq!(
            text.matches("<doOutput Value=\"0\"/>").count(),
            1,
            "the sheet is not cut"
        );
        assert!(
            text.contains("<VertList>V1 99V11 99V11 91V1 91</VertList>"),
            "y up: {text}"
        );
        assert!(text.contains("<PrimList>L0 1L1 2L2 3L3 0</PrimList>"), "closed");
        assert!(text.contains("<PrimList>L0 1</PrimList>"), "open");
        assert_eq!(text.matches("<CutSetting").count(), 4);
        assert!(text.contains("Notes=\"a &lt;b&gt; &amp; c\""), "the stock, escaped");
    }

    /// Each layer's power: the material's starting point, or the `laser` setting's own.
    #[test]
    fn powers_come_from_the_material_unless_the_laser_setting_gives_them() {
        let powers = |settings: &CutSettings| -> Vec<(String, String)> {
            let text = sheet_lbrn2((200.0, 100.0, 3.0), &[], settings, "s");
            let doc = roxmltree::Document::parse(&text).expect("XML");
            doc.descendants()
                .filter(|n| n.has_tag_name("CutSetting"))
                .map(|n| {
                    let value = |tag: &str| {
                        n.children()
                            .find(|c| c.has_tag_name(tag))
                            .and_then(|c| c.attribute("Value"))
                            .expect("a value")
                            .to_string()
                    };
                    assert_eq!(value("minPower"), value("maxPower"));
                    (value("name"), value("maxPower"))
                })
                .collect()
        };
        let by_material = powers(&CutSettings::default());
        assert_eq!(by_material[0], ("Engrave".to_string(), "20".to_string()));
        assert_eq!(by_material[1].1, "70", "wood's cutting power");
        let own = CutSettings {
            laser: crate::plan::laser::parse_laser("co2, cut-power=55, engrave-power=12.5").expect("a laser"),
            ..CutSettings::default()
        };
        let given = powers(&own);
        assert_eq!(
            given.iter().map(|(_, p)| p.as_str()).collect::<Vec<_>>(),
            ["12.5", "55", "55", "0"],
            "engrave, cut inner, cut outer, the sheet (off)"
        );
    }
}
