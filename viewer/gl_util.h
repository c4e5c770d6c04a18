// Small OpenGL 3.3 helpers shared by the viewer's GPU passes (gpu_display.h,
// gpu_moved_light.h): shaders compiled and linked with their log in the exception, 2D
// textures, texture units. All need the context current on the calling thread.
#pragma once

#include <epoxy/gl.h>

namespace relight::viewer::gl {

/// A vertex shader drawing one triangle that covers the viewport (glDrawArrays(GL_TRIANGLES,
/// 0, 3) with an empty vertex array); `uv` in [0, 1] over it.
extern const char* const kFullScreenVertexShader;

/// Compiles a shader; throws std::runtime_error with the driver's log when it does not.
GLuint compile(GLenum type, const char* source);
/// Links a program of these two shaders; throws std::runtime_error with the log.
GLuint link(const char* vertexSource, const char* fragmentSource);
/// A 2D texture of w x h texels, clamped at its edges, filtered as `filter`.
GLuint makeTexture2D(GLenum internalFormat, int w, int h, GLenum format, GLenum type,
                     const void* data, GLenum filter = GL_LINEAR);
/// Binds `tex` to texture unit `unit`.
void bindUnit(int unit, GLenum target, GLuint tex);

}  // namespace relight::viewer::gl
