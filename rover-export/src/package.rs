//! `rover export`: an FMU (modelDescription.xml, the prebuilt plant
//! library, the packed scenario) or a C library folder (header, static
//! library, example program, packed scenario).

use std::path::{Path, PathBuf};

use crate::error::ExportError;
use crate::instance::Instance;
use crate::model_description::{FmiVersion, Header, model_description};
use crate::resources::{ExportSettings, pack};
use crate::variables::{Inputs, Variables};
use crate::zip::{Entry, write_zip};

/// The C header of the library.
pub const HEADER: &str = include_str!("../c/rover_plant.h");
/// The example program.
pub const EXAMPLE: &str = include_str!("../c/main.c");
/// The library's base name: `librover_plant.so`, `librover_plant.a`.
pub const LIBRARY: &str = "rover_plant";
/// The environment variable naming the folder of the prebuilt libraries.
pub const LIBRARY_DIR_VAR: &str = "ROVER_PLANT_LIB_DIR";
/// The command that builds the prebuilt libraries.
pub const BUILD_COMMAND: &str = "cargo build -p rover-plant";

/// Which of the prebuilt libraries.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LibraryKind {
    /// The shared library an FMU carries.
    Shared,
    /// The static library the C export carries.
    Static,
}

/// The library's file name on this platform.
pub fn library_file(kind: LibraryKind) -> String {
    match kind {
        LibraryKind::Shared => format!(
            "{}{LIBRARY}{}",
            std::env::consts::DLL_PREFIX,
            std::env::consts::DLL_SUFFIX
        ),
        LibraryKind::Static if cfg!(windows) => format!("{LIBRARY}.lib"),
        LibraryKind::Static => format!("lib{LIBRARY}.a"),
    }
}

/// Find the prebuilt library: `explicit` when given, else in
/// `$ROVER_PLANT_LIB_DIR`, else beside the running executable (where
/// `cargo build` puts it with `rover`).
pub fn find_library(kind: LibraryKind, explicit: Option<&Path>) -> Result<PathBuf, ExportError> {
    if let Some(p) = explicit {
        return if p.is_file() {
            Ok(p.to_path_buf())
        } else {
            Err(ExportError::Library(format!(
                "--library {}: no such file; give the path of a plant library built with `{BUILD_COMMAND}` (target/debug/{})",
                p.display(),
                library_file(kind)
            )))
        };
    }
    let file = library_file(kind);
    let mut looked = Vec::new();
    if let Some(dir) = std::env::var_os(LIBRARY_DIR_VAR) {
        let p = PathBuf::from(dir).join(&file);
        if p.is_file() {
            return Ok(p);
        }
        looked.push(p);
    }
    if let Some(dir) = std::env::current_exe()
        .ok()
        .and_then(|e| e.parent().map(Path::to_path_buf))
    {
        // `cargo build -p rover-plant` puts it beside `rover`; `cargo
        // test`, which builds it as the tests' dependency, in `deps/`.
        for p in [dir.join(&file), dir.join("deps").join(&file)] {
            if p.is_file() {
                return Ok(p);
            }
            looked.push(p);
        }
    }
    Err(ExportError::Library(format!(
        "the prebuilt plant library {file} was not found (looked at {}): build it with `{BUILD_COMMAND}` (with `--release` for a release `rover`), which puts it beside the `rover` executable, or name it with --library or {LIBRARY_DIR_VAR}",
        looked
            .iter()
            .map(|p| p.display().to_string())
            .collect::<Vec<_>>()
            .join(", ")
    )))
}

/// The FMI platform folder of this machine, as `version` names it.
pub fn platform(version: FmiVersion) -> Result<&'static str, ExportError> {
    let (arch, os) = (std::env::consts::ARCH, std::env::consts::OS);
    let name = match (version, arch, os) {
        (FmiVersion::Fmi3, "x86_64", "linux") => "x86_64-linux",
        (FmiVersion::Fmi3, "aarch64", "linux") => "aarch64-linux",
        (FmiVersion::Fmi3, "x86_64", "macos") => "x86_64-darwin",
        (FmiVersion::Fmi3, "aarch64", "macos") => "aarch64-darwin",
        (FmiVersion::Fmi3, "x86_64", "windows") => "x86_64-windows",
        (FmiVersion::Fmi2, "x86_64", "linux") => "linux64",
        (FmiVersion::Fmi2, "x86_64", "macos") | (FmiVersion::Fmi2, "aarch64", "macos") => {
            "darwin64"
        }
        (FmiVersion::Fmi2, "x86_64", "windows") => "win64",
        _ => {
            return Err(ExportError::Usage(format!(
                "no FMI {} platform name for {arch}-{os}",
                if version == FmiVersion::Fmi3 {
                    "3.0"
                } else {
                    "2.0"
                }
            )));
        }
    };
    Ok(name)
}

/// A C identifier made of `text` (FMI's modelIdentifier must be one).
pub fn identifier(text: &str) -> String {
    let mut id: String = text
        .chars()
        .map(|c| if c.is_ascii_alphanumeric() { c } else { '_' })
        .collect();
    if !id.starts_with(|c: char| c.is_ascii_alphabetic()) {
        id.insert_str(0, "rover_");
    }
    id
}

/// What `rover export fmu` is asked.
#[derive(Clone, Debug)]
pub struct FmuOptions {
    /// A built-in rover or a description file (default: the scenario's).
    pub rover: Option<String>,
    /// The scenario file.
    pub scenario: PathBuf,
    /// The FMU to write.
    pub out: PathBuf,
    /// FMI 3.0 or 2.0.
    pub version: FmiVersion,
    /// The inputs the plant takes.
    pub inputs: Inputs,
    /// The shared plant library to carry.
    pub library: PathBuf,
}

/// What an export wrote.
#[derive(Clone, Debug)]
pub struct Written {
    /// The FMU or folder.
    pub path: PathBuf,
    /// Its model identifier (FMU) or library name (C).
    pub identifier: String,
    /// The number of outputs and of inputs.
    pub outputs: usize,
    /// The number of inputs.
    pub inputs: usize,
    /// What to run next (the C export's compile command).
    pub next: String,
}

/// A scratch folder under the system's temporary folder, removed when dropped.
struct Scratch(PathBuf);

impl Scratch {
    fn new(what: &str) -> Result<Self, ExportError> {
        let dir = std::env::temp_dir().join(format!(
            "rover-export-{what}-{}-{}",
            std::process::id(),
            std::time::SystemTime::now()
                .duration_since(std::time::UNIX_EPOCH)
                .map(|d| d.as_nanos())
                .unwrap_or(0)
        ));
        std::fs::create_dir_all(&dir)
            .map_err(|e| ExportError::io(&dir, "create a scratch folder", e))?;
        Ok(Scratch(dir))
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

/// Write the FMU `options` describe.
pub fn export_fmu(options: &FmuOptions) -> Result<Written, ExportError> {
    let platform = platform(options.version)?;
    let library = std::fs::read(&options.library)
        .map_err(|e| ExportError::io(&options.library, "read the plant library", e))?;
    let scratch = Scratch::new("fmu")?;
    let packed = pack(
        options.rover.as_deref(),
        &options.scenario,
        &scratch.0,
        options.inputs,
    )?;
    let spec = &packed.prepared.spec;
    let stem = options
        .scenario
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default();
    let model_identifier = identifier(&format!("{}_{stem}", spec.name));
    // The variables as the library will see them: the packed scenario opened.
    let instance = Instance::open_with(&scratch.0, packed.settings.clone(), crate::run::builtin)
        .map_err(ExportError::Usage)?;
    let vars: &Variables = &instance.vars;
    let description = format!(
        "The {} rover in scenario {} ({} inputs): rover-export's plant, stepping the scenario's integrator between communication points",
        spec.name,
        options.scenario.display(),
        match options.inputs {
            Inputs::None => "no",
            Inputs::Torques => "torque, steering and spring-neutral",
        }
    );
    let xml = model_description(
        options.version,
        &Header {
            model_name: &format!("{} {stem}", spec.name),
            model_identifier: &model_identifier,
            token: &packed.settings.token,
            description: &description,
            stop_time: instance.duration,
            step_size: instance.output_step(),
        },
        vars,
    );
    let mut entries = vec![
        Entry {
            name: "modelDescription.xml".into(),
            data: xml.into_bytes(),
        },
        Entry {
            name: format!(
                "binaries/{platform}/{model_identifier}{}",
                std::env::consts::DLL_SUFFIX
            ),
            data: library,
        },
    ];
    for name in &packed.files {
        let path = scratch.0.join(name);
        let data = std::fs::read(&path).map_err(|e| ExportError::io(&path, "read back", e))?;
        entries.push(Entry {
            name: format!("resources/{name}"),
            data,
        });
    }
    let mut bytes = Vec::new();
    write_zip(&mut bytes, &entries)
        .map_err(|e| ExportError::io(&options.out, "write the FMU", e))?;
    std::fs::write(&options.out, bytes)
        .map_err(|e| ExportError::io(&options.out, "write the FMU", e))?;
    let inputs = vars.list.iter().filter(|v| v.is_input()).count();
    Ok(Written {
        path: options.out.clone(),
        identifier: model_identifier,
        outputs: vars.list.len() - inputs - 1,
        inputs,
        next: String::new(),
    })
}

/// What `rover export c` is asked.
#[derive(Clone, Debug)]
pub struct COptions {
    /// A built-in rover or a description file (default: the scenario's).
    pub rover: Option<String>,
    /// The scenario file.
    pub scenario: PathBuf,
    /// The folder to write.
    pub out: PathBuf,
    /// The static plant library to carry.
    pub library: PathBuf,
}

/// The system libraries a Rust static library needs on this platform.
pub const NATIVE_LIBS: &str = if cfg!(target_os = "macos") {
    "-lSystem -lc -lm"
} else {
    "-lgcc_s -lutil -lrt -lpthread -lm -ldl -lc"
};

/// The command that compiles the example in the exported folder.
pub fn compile_command() -> String {
    format!("cc -O2 -I. main.c lib{LIBRARY}.a {NATIVE_LIBS} -o rover_main")
}

/// Write the C library folder `options` describe: `rover_plant.h`,
/// `librover_plant.a`, `main.c`, and `scenario/` (the packed scenario).
pub fn export_c(options: &COptions) -> Result<Written, ExportError> {
    let out = &options.out;
    std::fs::create_dir_all(out).map_err(|e| ExportError::io(out, "create the folder", e))?;
    let packed = pack(
        options.rover.as_deref(),
        &options.scenario,
        &out.join("scenario"),
        Inputs::Torques,
    )?;
    let write = |name: &str, bytes: &[u8]| {
        let p = out.join(name);
        std::fs::write(&p, bytes).map_err(|e| ExportError::io(&p, "write", e))
    };
    write("rover_plant.h", HEADER.as_bytes())?;
    write("main.c", EXAMPLE.as_bytes())?;
    let lib = out.join(library_file(LibraryKind::Static));
    std::fs::copy(&options.library, &lib)
        .map_err(|e| ExportError::io(&options.library, "copy the static library", e))?;
    let instance = Instance::open_with(
        &out.join("scenario"),
        packed.settings.clone(),
        crate::run::builtin,
    )
    .map_err(ExportError::Usage)?;
    let inputs = instance.vars.list.iter().filter(|v| v.is_input()).count();
    Ok(Written {
        path: out.clone(),
        identifier: LIBRARY.into(),
        outputs: instance.row().len(),
        inputs,
        next: format!(
            "cd {} && {} && ./rover_main",
            out.display(),
            compile_command()
        ),
    })
}

/// The settings of a packed folder, for tests and tools.
pub fn settings_of(dir: &Path) -> Result<ExportSettings, String> {
    ExportSettings::read(dir)
}
