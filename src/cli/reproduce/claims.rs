//! Every quantitative claim of the paper the report checks, in one list:
//! the paper's statement, the threshold we judge it by, our numbers and
//! whether it holds. A stored record says which claims held; a claim that
//! held there and holds no longer is a regression, and fails the command.
//! A claim known to fail (failing in the record too) is listed, with its
//! numbers, and does not.

use std::fmt::Write as _;
use std::path::Path;

use super::runs::other;
use crate::error::CliError;

/// One claim judged.
#[derive(Clone, Debug, PartialEq)]
pub struct Judged {
    /// Stable key of the claim in the stored record.
    pub id: String,
    pub figure: String,
    /// What the paper says.
    pub paper: String,
    /// How we judge it (ours where the paper is qualitative).
    pub threshold: String,
    /// Our numbers.
    pub ours: String,
    pub holds: bool,
    /// Whether a regression of this claim fails the command. Claims on
    /// wall times do not: they depend on the machine and its load (a
    /// criterion benchmark guards them).
    pub gate: bool,
}

/// What the record says of a claim.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Verdict {
    /// Holds (and held, or is not recorded).
    Holds,
    /// Holds now, failed in the record.
    Improved,
    /// Fails, as in the record: a known failure.
    Known,
    /// Fails and is not in the record.
    Fails,
    /// Held in the record and fails now.
    Regressed,
}

impl Judged {
    /// This claim against the stored record (`claim id → held`).
    pub fn verdict(&self, record: &[(String, bool)]) -> Verdict {
        let held = record.iter().find(|(id, _)| *id == self.id).map(|r| r.1);
        match (self.holds, held) {
            (true, Some(false)) => Verdict::Improved,
            (true, _) => Verdict::Holds,
            (false, Some(true)) => Verdict::Regressed,
            (false, Some(false)) => Verdict::Known,
            (false, None) => Verdict::Fails,
        }
    }
}

/// The claims that fail the command: they held in the record, fail now,
/// and are not judged on wall times.
pub fn regressions<'a>(claims: &'a [Judged], record: &[(String, bool)]) -> Vec<&'a Judged> {
    claims
        .iter()
        .filter(|c| c.gate && c.verdict(record) == Verdict::Regressed)
        .collect()
}

/// The figure's number ("Fig. 12", "Figs. 15–16" → 12, 15), for ordering.
fn figure_number(figure: &str) -> u32 {
    figure
        .chars()
        .skip_while(|c| !c.is_ascii_digit())
        .take_while(char::is_ascii_digit)
        .collect::<String>()
        .parse()
        .unwrap_or(u32::MAX)
}

/// The claims in the paper's order (by figure; claims of one figure keep
/// their order).
pub fn sorted(mut claims: Vec<Judged>) -> Vec<Judged> {
    claims.sort_by_key(|c| figure_number(&c.figure));
    claims
}

/// The claims as a Markdown table, each with its verdict against the
/// record.
pub fn table(claims: &[Judged], record: &[(String, bool)]) -> String {
    let mut t =
        String::from("| figure | paper | judged by | ours | holds |\n|---|---|---|---|---|\n");
    for c in claims {
        let verdict = match c.verdict(record) {
            Verdict::Holds => "yes".to_string(),
            Verdict::Improved => "yes (failed in the record)".to_string(),
            Verdict::Known => "**no** (known)".to_string(),
            Verdict::Fails => "**no** (not in the record)".to_string(),
            Verdict::Regressed if c.gate => "**no: regression**".to_string(),
            Verdict::Regressed => "**no** (held in the record; wall time, not a gate)".to_string(),
        };
        // A `|` inside a cell (|R/R_k − 1|) would end it.
        let cell = |s: &str| s.replace('|', "\\|");
        let _ = writeln!(
            t,
            "| {} | {} | {} | {} | {verdict} |",
            c.figure,
            cell(&c.paper),
            cell(&c.threshold),
            cell(&c.ours)
        );
    }
    t
}

/// How many claims hold, of how many.
pub fn tally(claims: &[Judged]) -> (usize, usize) {
    (claims.iter().filter(|c| c.holds).count(), claims.len())
}

const HEADER: &str = "claim,holds";

/// The record of which claims hold (`claim,holds` rows).
pub fn to_record(claims: &[Judged]) -> String {
    let mut s = String::from(HEADER);
    s.push('\n');
    for c in claims {
        let _ = writeln!(s, "{},{}", c.id, c.holds);
    }
    s
}

/// The record's rows from its text; `path` names it in errors.
pub fn parse_record(text: &str, path: &Path) -> Result<Vec<(String, bool)>, CliError> {
    let mut lines = text.lines();
    if lines.next() != Some(HEADER) {
        return Err(other(format!(
            "{}: not a record of claims (its first line should be `{HEADER}`); \
             make it again with `--record`",
            path.display()
        )));
    }
    lines
        .enumerate()
        .filter(|(_, l)| !l.trim().is_empty())
        .map(|(i, l)| {
            let bad = || {
                other(format!(
                    "{}:{}: expected `<claim>,true` or `<claim>,false`, found `{l}`; \
                     make the record again with `--record`",
                    path.display(),
                    i + 2
                ))
            };
            let (id, holds) = l.split_once(',').ok_or_else(bad)?;
            let holds = match holds {
                "true" => true,
                "false" => false,
                _ => return Err(bad()),
            };
            Ok((id.to_string(), holds))
        })
        .collect()
}

/// The record stored at `path`.
pub fn read_record(path: &Path) -> Result<Vec<(String, bool)>, CliError> {
    let text = rover_files::read_text(path, rover_files::Limit::Data).map_err(|e| {
        other(format!(
            "{}: {e} (make the record of which claims hold with `--record`)",
            path.display()
        ))
    })?;
    parse_record(&text, path)
}

/// An error naming every regression, or `Ok` when there is none.
pub fn check(claims: &[Judged], record: &[(String, bool)], what: &str) -> Result<(), CliError> {
    let broken: Vec<String> = regressions(claims, record)
        .iter()
        .map(|c| {
            format!(
                "{} \"{}\" no longer holds ({}): {}",
                c.figure, c.paper, c.threshold, c.ours
            )
        })
        .collect();
    if broken.is_empty() {
        Ok(())
    } else {
        Err(other(format!("{what}: {}", broken.join("; "))))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn claim(id: &str, holds: bool, gate: bool) -> Judged {
        Judged {
            id: id.into(),
            figure: "Fig. 12".into(),
            paper: "quite close".into(),
            threshold: "within 0.1 m".into(),
            ours: "0.2 m".into(),
            holds,
            gate,
        }
    }

    fn record(rows: &[(&str, bool)]) -> Vec<(String, bool)> {
        rows.iter().map(|(i, h)| (i.to_string(), *h)).collect()
    }

    #[test]
    fn a_claim_that_held_and_fails_now_fails_the_check() {
        let rec = record(&[("a", true), ("b", true)]);
        let now = [claim("a", true, true), claim("b", false, true)];
        assert_eq!(now[1].verdict(&rec), Verdict::Regressed);
        let err = check(&now, &rec, "report written").unwrap_err().to_string();
        assert!(
            err.contains("quite close") && err.contains("0.2 m"),
            "{err}"
        );
        assert!(table(&now, &rec).contains("regression"));
    }

    #[test]
    fn a_known_failure_is_listed_and_does_not_fail_the_check() {
        let rec = record(&[("a", true), ("b", false)]);
        let now = [claim("a", true, true), claim("b", false, true)];
        assert_eq!(now[1].verdict(&rec), Verdict::Known);
        assert!(check(&now, &rec, "x").is_ok());
        let t = table(&now, &rec);
        assert!(t.contains("**no** (known)") && t.contains("0.2 m"), "{t}");
    }

    #[test]
    fn a_new_claim_an_improvement_and_a_wall_time_claim_do_not_fail_the_check() {
        let rec = record(&[("b", false), ("c", true)]);
        let now = [
            claim("new", false, true),
            claim("b", true, true),
            claim("c", false, false),
        ];
        assert_eq!(now[0].verdict(&rec), Verdict::Fails);
        assert_eq!(now[1].verdict(&rec), Verdict::Improved);
        assert_eq!(now[2].verdict(&rec), Verdict::Regressed);
        assert!(regressions(&now, &rec).is_empty());
        assert!(check(&now, &rec, "x").is_ok());
    }

    #[test]
    fn the_record_round_trips_and_bad_rows_are_refused_with_the_line() {
        let now = [claim("fig5_a", true, true), claim("fig12_b", false, true)];
        let text = to_record(&now);
        let p = Path::new("claims.csv");
        assert_eq!(
            parse_record(&text, p).unwrap(),
            record(&[("fig5_a", true), ("fig12_b", false)])
        );
        let err = parse_record("claim,holds\nx,maybe\n", p)
            .unwrap_err()
            .to_string();
        assert!(
            err.contains("claims.csv:2") && err.contains("--record"),
            "{err}"
        );
        assert!(parse_record("id,ok\n", p).is_err());
    }

    #[test]
    fn claims_are_ordered_by_figure() {
        let mut a = claim("a", true, true);
        a.figure = "Figs. 15–16".into();
        let mut b = claim("b", true, true);
        b.figure = "Fig. 5".into();
        let mut c = claim("c", true, true);
        c.figure = "Fig. 11".into();
        let ids: Vec<String> = sorted(vec![a, b, c]).into_iter().map(|c| c.id).collect();
        assert_eq!(ids, ["b", "c", "a"]);
    }
}
