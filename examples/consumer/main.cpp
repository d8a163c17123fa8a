// Ray-traced ambient occlusion at a point of the built-in `plane` scene, through the installed library.
#include <obscura/builtin_scenes.h>
#include <obscura/trace.h>

#include <cstdio>

int main() {
    obscura::BuiltinScene plane = obscura::makeBuiltinScene("plane");
    obscura::trace::Tracer tracer(plane.scene);
    obscura::trace::ObscuranceSettings settings;
    settings.rays = 64;
    float a = obscura::trace::ambientObscurance(tracer, {0, 0, 0}, {0, 1, 0}, {0, 1, 0}, settings, 0);
    std::printf("plane AO %g\n", double(a));
    return a == 1.0f ? 0 : 1;
}
