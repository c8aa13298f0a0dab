//! With the feature `petsc`: finds PETSc and MPI with pkg-config and checks, with the C compiler,
//! every size and enum value that `src/ffi.rs` hard-codes. Without it: nothing (the stub needs
//! only the Rust toolchain).
//!
//! PETSc: `$PETSC_DIR[/$PETSC_ARCH]/lib/pkgconfig` if set (a source build), else pkg-config
//! `petsc` (Debian's). MPI: PETSc's .pc gives no MPI include directory, so `mpi-c`, `ompi-c` or
//! `mpich` is probed too.

fn main() {
    println!("cargo:rerun-if-changed=build.rs");
    println!("cargo::rustc-check-cfg=cfg(petsc_int64)");
    println!("cargo::rustc-check-cfg=cfg(mpi_comm_is_int)");
    #[cfg(feature = "petsc")]
    petsc::find();
}

#[cfg(feature = "petsc")]
mod petsc {
    use std::collections::HashMap;
    use std::env;
    use std::path::{Path, PathBuf};
    use std::process::Command;

    pub fn find() {
        for f in ["src/wrapper.h", "src/abi_check.c"] {
            println!("cargo:rerun-if-changed={f}");
        }
        for v in ["PETSC_DIR", "PETSC_ARCH", "PKG_CONFIG_PATH", "CC"] {
            println!("cargo:rerun-if-env-changed={v}");
        }
        if let Ok(dir) = env::var("PETSC_DIR") {
            let arch = env::var("PETSC_ARCH").unwrap_or_default();
            let pc = Path::new(&dir).join(arch).join("lib").join("pkgconfig");
            let old = env::var("PKG_CONFIG_PATH").unwrap_or_default();
            env::set_var("PKG_CONFIG_PATH", format!("{}:{old}", pc.display()));
        }
        let petsc = pkg_config::Config::new()
            .atleast_version("3.18")
            .probe("petsc")
            .unwrap_or_else(|e| {
                panic!(
                    "PETSc not found by pkg-config ({e}).\n  Debian/Ubuntu: apt-get install \
                     libpetsc-real3.18-dev\n  a source build: set PETSC_DIR and PETSC_ARCH"
                )
            });
        let mpi = ["mpi-c", "ompi-c", "mpich"]
            .iter()
            .find_map(|name| pkg_config::probe_library(name).ok())
            .expect("MPI not found by pkg-config (mpi-c, ompi-c, mpich)");
        // A source build's libpetsc is not on the loader's path (Debian's is: harmless there).
        for p in &petsc.link_paths {
            println!("cargo:rustc-link-arg=-Wl,-rpath,{}", p.display());
        }
        let includes: Vec<PathBuf> = petsc
            .include_paths
            .iter()
            .chain(&mpi.include_paths)
            .cloned()
            .collect();
        let defs = macros(&includes);
        let int64 = defs.contains_key("PETSC_USE_64BIT_INDICES");
        let openmpi = defs.contains_key("OMPI_MAJOR_VERSION");
        let mpich = defs.contains_key("MPICH_VERSION");
        assert!(openmpi || mpich, "unknown MPI (neither Open MPI nor MPICH)");
        if int64 {
            println!("cargo:rustc-cfg=petsc_int64");
        }
        if mpich {
            // MPICH: typedef int MPI_Comm; Open MPI: a pointer.
            println!("cargo:rustc-cfg=mpi_comm_is_int");
        }
        let ver = |k: &str| defs.get(k).cloned().unwrap_or_default();
        println!(
            "cargo:rustc-env=HERTZ_PETSC_VERSION={}.{}.{}",
            ver("PETSC_VERSION_MAJOR"),
            ver("PETSC_VERSION_MINOR"),
            ver("PETSC_VERSION_SUBMINOR")
        );
        abi_check(
            &includes,
            if int64 { 8 } else { 4 },
            if mpich { 4 } else { 8 },
        );
    }

    fn cc() -> String {
        env::var("CC").unwrap_or_else(|_| "cc".into())
    }

    fn include_args(includes: &[PathBuf]) -> Vec<String> {
        includes
            .iter()
            .map(|p| format!("-I{}", p.display()))
            .collect()
    }

    /// `cc -E -dM src/wrapper.h`: the macros visible after including petscksp.h.
    fn macros(includes: &[PathBuf]) -> HashMap<String, String> {
        let out = Command::new(cc())
            .args(["-E", "-dM"])
            .args(include_args(includes))
            .arg("src/wrapper.h")
            .output()
            .expect("running the C compiler (set CC)");
        assert!(
            out.status.success(),
            "preprocessing petscksp.h failed:\n{}",
            String::from_utf8_lossy(&out.stderr)
        );
        String::from_utf8_lossy(&out.stdout)
            .lines()
            .filter_map(|l| l.strip_prefix("#define "))
            .map(|l| {
                let mut it = l.splitn(2, ' ');
                let name = it.next().unwrap_or("").to_string();
                (name, it.next().unwrap_or("").trim().to_string())
            })
            .collect()
    }

    /// The C compiler checks the sizes and enum values `src/ffi.rs` hard-codes.
    fn abi_check(includes: &[PathBuf], int_size: usize, comm_size: usize) {
        let out = Command::new(cc())
            .arg("-fsyntax-only")
            .arg(format!("-DEXPECT_PETSCINT_SIZE={int_size}"))
            .arg(format!("-DEXPECT_MPI_COMM_SIZE={comm_size}"))
            .args(include_args(includes))
            .arg("src/abi_check.c")
            .output()
            .expect("running the C compiler (set CC)");
        assert!(
            out.status.success(),
            "ABI check failed:\n{}",
            String::from_utf8_lossy(&out.stderr)
        );
    }
}
