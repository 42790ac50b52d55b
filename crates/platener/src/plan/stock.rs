//! The stock list (`stock`, issue 34): the sheets a maker has, per thickness, with sizes and
//! counts (`3:600x400x2, 3:300x200, 6:300x200x1`), nested onto in the order listed, so
//! offcuts listed first are used first.

use serde::{Deserialize, Serialize};

/// Sheets of one size and thickness the maker has.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct StockSheet {
    /// The thickness they are sold as, mm (matched against the nominal thickness of a
    /// measured sheet).
    pub thickness: f64,
    /// Width, mm.
    pub width: f64,
    /// Height, mm.
    pub height: f64,
    /// How many; `None` for as many as needed.
    pub count: Option<u32>,
}

/// The most sheets one entry may count (more is "as many as needed": leave the count out).
pub const MAX_STOCK_COUNT: u32 = 1000;
/// The most entries a stock list may have.
pub const MAX_STOCK_ENTRIES: usize = 20;

impl StockSheet {
    /// The entry as the setting writes it: `3:600x400x2`, or `3:600x400` without a count.
    pub fn text(&self) -> String {
        let count = self.count.map_or(String::new(), |n| format!("x{n}"));
        format!("{}:{}x{}{count}", self.thickness, self.width, self.height)
    }
}

/// Reads a stock list, entries `T:WxH[xN]` separated by commas or spaces; the empty text is
/// no stock. The error is a phrase for the page, naming the entry.
pub fn parse_stock(text: &str, max_side: f64) -> Result<Vec<StockSheet>, String> {
    let entries: Vec<&str> = text
        .split([',', ';', ' '])
        .map(str::trim)
        .filter(|e| !e.is_empty())
        .collect();
    if entries.len() > MAX_STOCK_ENTRIES {
        return Err(format!("takes at most {MAX_STOCK_ENTRIES} kinds of sheet"));
    }
    entries.into_iter().map(|e| parse_entry(e, max_side)).collect()
}

fn parse_entry(entry: &str, max_side: f64) -> Result<StockSheet, String> {
    let bad = || format!("{entry:?} must be thickness:widthxheight[xcount] in mm, e.g. 3:600x400x2");
    let (t, size) = entry.split_once(':').ok_or_else(bad)?;
    let numbers: Vec<&str> = size.split(['x', 'X', '×', '*']).collect();
    let number = |s: &str| s.trim().parse::<f64>().ok().filter(|v| v.is_finite() && *v > 0.0);
    let (Some(thickness), [w, h, rest @ ..]) = (number(t), numbers.as_slice()) else {
        return Err(bad());
    };
    let (Some(width), Some(height)) = (number(w), number(h)) else {
        return Err(bad());
    };
    let count = match rest {
        [] => None,
        [n] => match n.trim().parse::<u32>() {
            Ok(n) if (1..=MAX_STOCK_COUNT).contains(&n) => Some(n),
            _ => {
                return Err(format!(
                    "{entry:?}: the count must be a whole number from 1 to {MAX_STOCK_COUNT}"
                ));
            }
        },
        _ => return Err(bad()),
    };
    if width > max_side || height > max_side {
        return Err(format!("{entry:?}: each side must be at most {max_side} mm"));
    }
    Ok(StockSheet {
        thickness,
        width,
        height,
        count,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn entries_read_with_and_without_counts_and_write_back() {
        let stock = parse_stock("3:600x400x2, 3:300x200 6:300×200x1", 10_000.0).expect("valid");
        assert_eq!(
            stock,
            vec![
                StockSheet {
                    thickness: 3.0,
                    width: 600.0,
                    height: 400.0,
                    count: Some(2)
                },
                StockSheet {
                    thickness: 3.0,
                    width: 300.0,
                    height: 200.0,
                    count: None
                },
                StockSheet {
                    thickness: 6.0,
                    width: 300.0,
                    height: 200.0,
                    count: Some(1)
                },
            ]
        );
        let text: Vec<String> = stock.iter().map(StockSheet::text).collect();
        assert_eq!(text.join(","), "3:600x400x2,3:300x200,6:300x200x1");
        assert!(parse_stock("", 10_000.0).expect("none").is_empty());
    }

    #[test]
    fn bad_entries_are_named() {
        for (text, says) in [
            ("3-600x400", "thickness:widthxheight"),
            ("3:600", "thickness:widthxheight"),
            ("3:600x400x0", "count"),
            ("3:600x400x1.5", "count"),
            ("3:20000x400", "at most"),
            ("x:600x400", "thickness:widthxheight"),
        ] {
            let e = parse_stock(text, 10_000.0).expect_err(text);
            assert!(e.contains(says) && e.contains(text), "{text}: {e}");
        }
    }
}
