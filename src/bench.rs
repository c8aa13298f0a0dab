//! `hertz bench`: placeholder replaced below.
pub fn main(_args: &[String]) -> std::process::ExitCode {
    std::process::ExitCode::from(2)
}
