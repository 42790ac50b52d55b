//! The laser (`laser`, issue 35): which kind of machine cuts the sheets, and any speed the
//! maker knows better. It gives the speeds the time estimate and the LightBurn project use,
//! per material and thickness.
//!
//! The table is for the profile `co2`, a typical 40–60 W CO₂ tube with air assist, one pass:
//! mid-points of published starting settings (a 60 W settings reference: 3 mm birch plywood
//! 12–18 mm/s, 6 mm 5–8; 3 mm cast acrylic 10–15, 6 mm 5–8; 2 mm cardboard 25–35; 0.2 mm
//! paper 40–60; a 40 W plywood guide: 3 mm 20–30, 6 mm 10–15; sources in
//! docs/cutting-plans.md). Between two listed thicknesses the speed is interpolated on a log
//! scale (cutting speed falls about as 1/thickness); past the thickest it falls as
//! 1/thickness, below the thinnest it stays. Other profiles scale the table by a factor: a
//! 100 W tube cuts about 1.8× as fast, a K40 (a "40 W" tube giving about 30) about half as
//! fast, a 10 W diode about 1/16 (3 mm plywood takes it 4–6 passes at 4 mm/s) and a 20 W
//! diode about 1/5.

use serde::{Deserialize, Deserializer, Serialize, Serializer};

use super::settings::Material;

/// A kind of laser cutter, setting the speeds unless the maker gives their own.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum LaserKind {
    /// A 40–60 W CO₂ tube with air assist (fab labs' Epilog, Trotec, Glowforge Pro class).
    #[default]
    Co2,
    /// A 100 W CO₂ tube.
    Co2Strong,
    /// A K40: sold as 40 W, about 30 W in practice.
    K40,
    /// A 10 W (optical) diode module.
    Diode10,
    /// A 20 W (optical) diode module.
    Diode20,
}

impl LaserKind {
    /// Every kind, in the order the docs list them.
    pub const ALL: [LaserKind; 5] = [
        LaserKind::Co2,
        LaserKind::Co2Strong,
        LaserKind::K40,
        LaserKind::Diode10,
        LaserKind::Diode20,
    ];

    /// The name the setting takes.
    pub fn name(self) -> &'static str {
        match self {
            LaserKind::Co2 => "co2",
            LaserKind::Co2Strong => "co2-100w",
            LaserKind::K40 => "k40",
            LaserKind::Diode10 => "diode-10w",
            LaserKind::Diode20 => "diode-20w",
        }
    }

    /// Its cutting speed over the `co2` table's (see the module docs).
    pub fn cut_factor(self) -> f64 {
        match self {
            LaserKind::Co2 => 1.0,
            LaserKind::Co2Strong => 1.8,
            LaserKind::K40 => 0.5,
            LaserKind::Diode10 => 1.0 / 16.0,
            LaserKind::Diode20 => 0.2,
        }
    }

    /// Its speed with the beam off, mm/s: gantry CO₂ machines move faster than the belts of
    /// open-frame diode machines.
    fn travel(self) -> f64 {
        match self {
            LaserKind::Co2 | LaserKind::Co2Strong => 300.0,
            LaserKind::K40 => 200.0,
            LaserKind::Diode10 | LaserKind::Diode20 => 150.0,
        }
    }
}

/// Cutting speeds of the `co2` profile: (thickness mm, speed mm/s), by thickness.
fn cut_table(material: Material) -> &'static [(f64, f64)] {
    match material {
        Material::Wood => &[(1.5, 25.0), (3.0, 15.0), (4.0, 11.0), (6.0, 6.5), (9.0, 3.5)],
        Material::Acrylic => &[
            (2.0, 16.0),
            (3.0, 12.5),
            (5.0, 8.0),
            (6.0, 6.5),
            (8.0, 4.0),
            (10.0, 2.5),
        ],
        Material::Cardboard => &[(1.0, 40.0), (2.0, 30.0), (3.0, 22.0), (5.0, 14.0)],
        Material::Paper => &[(0.2, 50.0), (0.5, 45.0), (1.0, 40.0)],
    }
}

/// Vector engraving and scoring speed of the `co2` profile, mm/s (low power, fast).
fn engrave_speed(material: Material) -> f64 {
    match material {
        Material::Wood | Material::Acrylic => 150.0,
        Material::Cardboard => 200.0,
        Material::Paper => 250.0,
    }
}

/// Seconds each cut path costs beyond its length: the head slows to a stop, the beam
/// pierces, the head accelerates again.
const PIERCE_SECONDS: f64 = 0.2;

/// The cutting speed of the `co2` profile for `material` sheets `thickness` mm thick, mm/s.
pub fn table_cut_speed(material: Material, thickness: f64) -> f64 {
    let table = cut_table(material);
    let (first, last) = (table[0], table[table.len() - 1]);
    if thickness <= first.0 {
        return first.1;
    }
    if thickness >= last.0 {
        return last.1 * last.0 / thickness;
    }
    let k = table.partition_point(|&(t, _)| t <= thickness);
    let ((t0, v0), (t1, v1)) = (table[k - 1], table[k]);
    if t0 == thickness {
        return v0;
    }
    let f = (thickness / t0).ln() / (t1 / t0).ln();
    (v0.ln() + f * (v1.ln() - v0.ln())).exp()
}

/// The laser setting: a kind and the speeds the maker set themselves.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Laser {
    /// The machine.
    pub kind: LaserKind,
    /// Cutting speed, mm/s, for every sheet; `None` takes the table's.
    pub cut: Option<f64>,
    /// Engraving and scoring speed, mm/s.
    pub engrave: Option<f64>,
    /// Speed with the beam off, mm/s.
    pub travel: Option<f64>,
    /// Seconds per cut path started.
    pub pierce: Option<f64>,
    /// Cutting power in the LightBurn project, per cent of the tube; `None` takes the
    /// material's starting point (`export::lightburn::power`).
    pub cut_power: Option<f64>,
    /// Engraving and scoring power, per cent.
    pub engrave_power: Option<f64>,
}

/// The speeds one sheet is cut with.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct LaserSpeeds {
    /// Cutting, mm/s.
    pub cut: f64,
    /// Engraving and scoring, mm/s.
    pub engrave: f64,
    /// With the beam off, mm/s.
    pub travel: f64,
    /// Per cut path started, s.
    pub pierce: f64,
}

/// The keys a laser setting may set, with what each is.
pub const LASER_KEYS: [(&str, &str); 6] = [
    ("cut", "cutting speed, mm/s"),
    ("engrave", "engraving and scoring speed, mm/s"),
    ("travel", "speed with the beam off, mm/s"),
    ("pierce", "seconds per cut started"),
    ("cut-power", "cutting power, % of the tube"),
    ("engrave-power", "engraving and scoring power, % of the tube"),
];

impl Laser {
    /// The speeds for sheets of `material`, `thickness` mm thick.
    pub fn speeds(&self, material: Material, thickness: f64) -> LaserSpeeds {
        let factor = self.kind.cut_factor();
        LaserSpeeds {
            cut: self
                .cut
                .unwrap_or_else(|| table_cut_speed(material, thickness) * factor),
            engrave: self
                .engrave
                .unwrap_or_else(|| engrave_speed(material) * factor.min(1.0)),
            travel: self.travel.unwrap_or_else(|| self.kind.travel()),
            pierce: self.pierce.unwrap_or(PIERCE_SECONDS),
        }
    }

    /// The setting as written: the kind, then what the maker set (`co2, cut=12`).
    pub fn text(&self) -> String {
        let mut out = self.kind.name().to_string();
        for (key, value) in [
            ("cut", self.cut),
            ("engrave", self.engrave),
            ("travel", self.travel),
            ("pierce", self.pierce),
            ("cut-power", self.cut_power),
            ("engrave-power", self.engrave_power),
        ] {
            if let Some(v) = value {
                out.push_str(&format!(", {key}={v}"));
            }
        }
        out
    }
}

/// Reads a laser setting: a kind (`co2`, `co2-100w`, `k40`, `diode-10w`, `diode-20w`) and/or
/// `key=value` pairs (`cut=12, travel=400, cut-power=55`), separated by commas or spaces. The error is a
/// phrase for the page.
pub fn parse_laser(text: &str) -> Result<Laser, String> {
    let mut laser = Laser::default();
    for item in text.split([',', ';', ' ']).map(str::trim).filter(|e| !e.is_empty()) {
        let Some((key, value)) = item.split_once('=') else {
            laser.kind = LaserKind::ALL
                .into_iter()
                .find(|k| k.name().eq_ignore_ascii_case(item))
                .ok_or_else(|| {
                    let names: Vec<&str> = LaserKind::ALL.iter().map(|k| k.name()).collect();
                    format!("{item:?} is not a laser; choose one of {}", names.join(", "))
                })?;
            continue;
        };
        let value: f64 = value
            .trim()
            .parse()
            .ok()
            .filter(|v: &f64| v.is_finite() && *v > 0.0 && *v <= 10_000.0)
            .ok_or_else(|| format!("{item:?}: the value must be a positive number"))?;
        let key = key.trim().to_ascii_lowercase();
        let slot = match key.as_str() {
            "cut" => &mut laser.cut,
            "engrave" => &mut laser.engrave,
            "travel" => &mut laser.travel,
            "pierce" => &mut laser.pierce,
            "cut-power" => &mut laser.cut_power,
            "engrave-power" => &mut laser.engrave_power,
            other => {
                let keys: Vec<&str> = LASER_KEYS.iter().map(|(k, _)| *k).collect();
                return Err(format!("{other:?} is not a laser setting; give {}", keys.join(", ")));
            }
        };
        if key.ends_with("-power") && value > 100.0 {
            return Err(format!("{item:?}: a power is a per cent of the tube, at most 100"));
        }
        *slot = Some(value);
    }
    Ok(laser)
}

impl Serialize for Laser {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(&self.text())
    }
}

impl<'de> Deserialize<'de> for Laser {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let text = String::deserialize(d)?;
        parse_laser(&text).map_err(serde::de::Error::custom)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_table_gives_its_own_points_and_falls_between_them() {
        assert_eq!(table_cut_speed(Material::Wood, 3.0), 15.0);
        assert_eq!(table_cut_speed(Material::Acrylic, 6.0), 6.5);
        let between = table_cut_speed(Material::Wood, 5.0);
        assert!(between < 11.0 && between > 6.5, "{between}");
        // Past the table: as 1/thickness; below it: the thinnest's speed.
        assert!((table_cut_speed(Material::Wood, 18.0) - 1.75).abs() < 1e-12);
        assert_eq!(table_cut_speed(Material::Paper, 0.1), 50.0);
    }

    #[test]
    fn a_setting_reads_back_as_written() {
        let laser = parse_laser("diode-10w, cut=3.5 travel=120").expect("a laser");
        assert_eq!(laser.kind, LaserKind::Diode10);
        assert_eq!(laser.cut, Some(3.5));
        assert_eq!(laser.travel, Some(120.0));
        assert_eq!(parse_laser(&laser.text()).expect("reads back"), laser);
        let speeds = laser.speeds(Material::Wood, 3.0);
        assert_eq!((speeds.cut, speeds.travel, speeds.pierce), (3.5, 120.0, 0.2));
        // The diode's engraving is slower than the tube's by its factor.
        assert!((speeds.engrave - 150.0 / 16.0).abs() < 1e-12);
    }

    #[test]
    fn powers_read_back_and_stay_within_the_tube() {
        let laser = parse_laser("co2, cut-power=55 engrave-power=12.5").expect("a laser");
        assert_eq!((laser.cut_power, laser.engrave_power), (Some(55.0), Some(12.5)));
        assert_eq!(laser.text(), "co2, cut-power=55, engrave-power=12.5");
        assert_eq!(parse_laser(&laser.text()).expect("reads back"), laser);
        assert!(
            parse_laser("cut-power=120")
                .expect_err("over 100")
                .contains("at most 100")
        );
        assert!(parse_laser("cut-power=0").expect_err("zero").contains("positive"));
    }

    #[test]
    fn a_bad_setting_names_what_is_wrong() {
        assert!(parse_laser("co3").expect_err("no such laser").contains("co2-100w"));
        assert!(parse_laser("cut=-1").expect_err("negative").contains("positive"));
        assert!(
            parse_laser("speed=3")
                .expect_err("no such key")
                .contains("cut, engrave, travel, pierce")
        );
        assert_eq!(parse_laser("").expect("empty is the default"), Laser::default());
    }
}
