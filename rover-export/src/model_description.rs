//! `modelDescription.xml` of an exported plant, FMI 3.0 or 2.0
//! Co-Simulation: the variables of [`Variables`] with their units, the
//! outputs and initial unknowns, the scenario's duration and output
//! interval as the default experiment.

use std::fmt::Write;

use crate::variables::{Role, Variables};

/// The FMI version of an export.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FmiVersion {
    /// FMI 2.0 Co-Simulation.
    Fmi2,
    /// FMI 3.0 Co-Simulation.
    Fmi3,
}

/// What the description says besides the variables.
#[derive(Clone, Debug)]
pub struct Header<'a> {
    /// The model's name (the rover's and the scenario's).
    pub model_name: &'a str,
    /// The name of the library in `binaries/<platform>/`, without extension.
    pub model_identifier: &'a str,
    /// The instantiation token (FMI 2's GUID).
    pub token: &'a str,
    /// A sentence on what the model is.
    pub description: &'a str,
    /// The default stop time \[s\].
    pub stop_time: f64,
    /// The default communication step \[s\].
    pub step_size: f64,
}

/// The SI base-unit exponents of each unit the variables use (the
/// attributes of `<BaseUnit>`).
fn base_unit(unit: &str) -> &'static str {
    match unit {
        "s" => r#"s="1""#,
        "m" => r#"m="1""#,
        "rad" => r#"rad="1""#,
        "m/s" => r#"m="1" s="-1""#,
        "rad/s" => r#"rad="1" s="-1""#,
        "N" => r#"kg="1" m="1" s="-2""#,
        "N.m" => r#"kg="1" m="2" s="-2""#,
        _ => "",
    }
}

/// `text` escaped for an XML attribute.
fn escape(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            c => out.push(c),
        }
    }
    out
}

/// The units used, each once, in order of first use.
fn units(vars: &Variables) -> Vec<&'static str> {
    let mut seen: Vec<&'static str> = Vec::new();
    for v in &vars.list {
        if !v.unit.is_empty() && !seen.contains(&v.unit) {
            seen.push(v.unit);
        }
    }
    seen
}

/// The model description of `vars` as `version` writes it.
pub fn model_description(version: FmiVersion, header: &Header<'_>, vars: &Variables) -> String {
    let mut x = String::new();
    let h = header;
    let tool = concat!("rover-export ", env!("CARGO_PKG_VERSION"));
    x.push_str("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n");
    match version {
        FmiVersion::Fmi3 => {
            let _ = writeln!(
                x,
                "<fmiModelDescription fmiVersion=\"3.0\" modelName=\"{}\" instantiationToken=\"{}\" description=\"{}\" generationTool=\"{tool}\" variableNamingConvention=\"flat\">",
                escape(h.model_name),
                escape(h.token),
                escape(h.description)
            );
            let _ = writeln!(
                x,
                "  <CoSimulation modelIdentifier=\"{}\" canHandleVariableCommunicationStepSize=\"true\" canGetAndSetFMUState=\"false\" canSerializeFMUState=\"false\" providesDirectionalDerivatives=\"false\" providesAdjointDerivatives=\"false\" hasEventMode=\"false\"/>",
                escape(h.model_identifier)
            );
        }
        FmiVersion::Fmi2 => {
            let _ = writeln!(
                x,
                "<fmiModelDescription fmiVersion=\"2.0\" modelName=\"{}\" guid=\"{}\" description=\"{}\" generationTool=\"{tool}\" variableNamingConvention=\"flat\" numberOfEventIndicators=\"0\">",
                escape(h.model_name),
                escape(h.token),
                escape(h.description)
            );
            let _ = writeln!(
                x,
                "  <CoSimulation modelIdentifier=\"{}\" canHandleVariableCommunicationStepSize=\"true\" canNotUseMemoryManagementFunctions=\"true\" canGetAndSetFMUstate=\"false\" canSerializeFMUstate=\"false\"/>",
                escape(h.model_identifier)
            );
        }
    }
    x.push_str("  <UnitDefinitions>\n");
    for u in units(vars) {
        let _ = writeln!(
            x,
            "    <Unit name=\"{}\"><BaseUnit {}/></Unit>",
            escape(u),
            base_unit(u)
        );
    }
    x.push_str("  </UnitDefinitions>\n");
    let _ = writeln!(
        x,
        "  <DefaultExperiment startTime=\"0\" stopTime=\"{}\" stepSize=\"{}\"/>",
        h.stop_time, h.step_size
    );
    x.push_str("  <ModelVariables>\n");
    for v in &vars.list {
        let (causality, start) = match v.role {
            Role::Time => ("independent", None),
            Role::Output(_) => ("output", None),
            _ => ("input", Some(v.start)),
        };
        let unit = if v.unit.is_empty() {
            String::new()
        } else {
            format!(" unit=\"{}\"", escape(v.unit))
        };
        let start = start
            .map(|s| format!(" start=\"{s:?}\""))
            .unwrap_or_default();
        match version {
            FmiVersion::Fmi3 => {
                let _ = writeln!(
                    x,
                    "    <Float64 name=\"{}\" valueReference=\"{}\" description=\"{}\" causality=\"{causality}\" variability=\"continuous\"{unit}{start}/>",
                    escape(&v.name),
                    v.value_reference,
                    escape(&v.description)
                );
            }
            FmiVersion::Fmi2 => {
                let initial = if causality == "output" {
                    " initial=\"calculated\""
                } else {
                    ""
                };
                let _ = writeln!(
                    x,
                    "    <ScalarVariable name=\"{}\" valueReference=\"{}\" description=\"{}\" causality=\"{causality}\" variability=\"continuous\"{initial}><Real{unit}{start}/></ScalarVariable>",
                    escape(&v.name),
                    v.value_reference,
                    escape(&v.description)
                );
            }
        }
    }
    x.push_str("  </ModelVariables>\n  <ModelStructure>\n");
    let outputs: Vec<usize> = (0..vars.list.len())
        .filter(|&k| matches!(vars.list[k].role, Role::Output(_)))
        .collect();
    match version {
        FmiVersion::Fmi3 => {
            for &k in &outputs {
                let _ = writeln!(
                    x,
                    "    <Output valueReference=\"{}\"/>",
                    vars.list[k].value_reference
                );
            }
            for &k in &outputs {
                let _ = writeln!(
                    x,
                    "    <InitialUnknown valueReference=\"{}\"/>",
                    vars.list[k].value_reference
                );
            }
        }
        FmiVersion::Fmi2 => {
            // FMI 2 names a variable by its 1-based position in ModelVariables.
            x.push_str("    <Outputs>\n");
            for &k in &outputs {
                let _ = writeln!(x, "      <Unknown index=\"{}\"/>", k + 1);
            }
            x.push_str("    </Outputs>\n    <InitialUnknowns>\n");
            for &k in &outputs {
                let _ = writeln!(x, "      <Unknown index=\"{}\"/>", k + 1);
            }
            x.push_str("    </InitialUnknowns>\n");
        }
    }
    x.push_str("  </ModelStructure>\n</fmiModelDescription>\n");
    x
}
