//! Reading what a conversion links to: its `/api/…` links and the part count of a plan ZIP.

use std::io::Read as _;

use serde_json::Value;

/// Every `/api/…` link in a conversion's `links`, depth first.
pub fn all_links(v: &Value, out: &mut Vec<String>) {
    match v {
        Value::String(s) if s.starts_with("/api/") => out.push(s.clone()),
        Value::Array(a) => a.iter().for_each(|x| all_links(x, out)),
        Value::Object(o) => o.values().for_each(|x| all_links(x, out)),
        _ => {}
    }
}

/// The parts in a ZIP's plan.json (panics when the ZIP does not open or the plan does not parse).
pub fn zip_parts(zip: &[u8]) -> usize {
    let mut archive = zip::ZipArchive::new(std::io::Cursor::new(zip)).expect("a ZIP");
    let mut plan = String::new();
    archive
        .by_name("plan.json")
        .expect("plan.json in the ZIP")
        .read_to_string(&mut plan)
        .expect("text");
    let plan: Value = serde_json::from_str(&plan).expect("JSON");
    plan["parts"].as_array().expect("parts").len()
}
