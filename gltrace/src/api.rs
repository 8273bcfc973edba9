//! The API a capture's calls belong to (OpenGL through GLX/WGL/CGL, EGL,
//! Direct3D), decided from function names as apitrace decides it.

/// The API a capture's calls belong to, decided as apitrace decides it:
/// by the first function whose name belongs to a window-system API.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Api {
    /// OpenGL through GLX, WGL or CGL (`glX*`, `wgl[A-Z]*`, `CGL*`).
    Gl,
    /// OpenGL or OpenGL ES through EGL (`egl[A-Z]*`).
    Egl,
    /// Direct3D or DirectDraw (`Direct*`, `D3D*`, `Create*`).
    Dx,
    /// No call (within the first ones read) names an API.
    Unknown,
}

impl Api {
    /// The API a function's name belongs to, or [`Api::Unknown`].
    pub fn from_function(name: &str) -> Api {
        let b = name.as_bytes();
        let upper_at = |i: usize| b.get(i).is_some_and(u8::is_ascii_uppercase);
        if name.starts_with("glX")
            || (name.starts_with("wgl") && upper_at(3))
            || name.starts_with("CGL")
        {
            Api::Gl
        } else if name.starts_with("egl") && upper_at(3) {
            Api::Egl
        } else if name.starts_with("Direct")
            || name.starts_with("D3D")
            || name.starts_with("Create")
        {
            Api::Dx
        } else {
            Api::Unknown
        }
    }

    /// A name for messages.
    pub fn describe(self) -> &'static str {
        match self {
            Api::Gl => "OpenGL (GLX/WGL/CGL)",
            Api::Egl => "OpenGL or OpenGL ES (EGL)",
            Api::Dx => "Direct3D/DirectDraw",
            Api::Unknown => "no API (no call names GLX, WGL, CGL, EGL or Direct3D)",
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn window_system_functions_name_the_api_and_gl_calls_do_not() {
        assert_eq!(Api::from_function("glXChooseVisual"), Api::Gl);
        assert_eq!(Api::from_function("wglCreateContext"), Api::Gl);
        assert_eq!(Api::from_function("CGLChoosePixelFormat"), Api::Gl);
        assert_eq!(Api::from_function("eglGetDisplay"), Api::Egl);
        assert_eq!(Api::from_function("Direct3DCreate9"), Api::Dx);
        assert_eq!(Api::from_function("CreateDXGIFactory"), Api::Dx);
        // A GL call, a lower-case letter after `wgl`/`egl`, a short name.
        for name in ["glClear", "wglx", "eglx", "egl", ""] {
            assert_eq!(Api::from_function(name), Api::Unknown, "{name}");
        }
    }
}
