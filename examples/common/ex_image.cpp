// ex_image.cpp — see ex_image.h. The only C++ in examples/common: OpenImageIO 2.4.
#include "ex_image.h"

#include <OpenImageIO/imageio.h>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <unistd.h>
#include <vector>

extern "C" char *program_invocation_short_name; // glibc

namespace {

enum class Format { png, exr, unknown };

std::string extension_of(const std::string &path)
{
    size_t dot = path.find_last_of('.'), slash = path.find_last_of('/');
    if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
    std::string e = path.substr(dot);
    for (auto &c : e) c = (char)std::tolower((unsigned char)c);
    return e;
}

Format format_of(const std::string &path)
{
    std::string e = extension_of(path);
    return e == ".png" ? Format::png : e == ".exr" ? Format::exr : Format::unknown;
}

// OIIO messages may span lines; the examples promise one line.
std::string one_line(std::string s)
{
    for (auto &c : s)
        if (c == '\n' || c == '\r') c = ' ';
    while (!s.empty() && s.back() == ' ') s.pop_back();
    return s.empty() ? "unknown OpenImageIO error" : s;
}

int fail(const char *verb, const char *path, const std::string &why)
{
    std::fprintf(stderr, "%s: cannot %s %s: %s\n", program_invocation_short_name, verb, path, one_line(why).c_str());
    return -1;
}

// Why a file in this directory cannot be created, or "" if it seems it can.
std::string directory_problem(const std::string &path)
{
    size_t slash = path.find_last_of('/');
    std::string dir = slash == std::string::npos ? "." : slash == 0 ? "/" : path.substr(0, slash);
    if (access(dir.c_str(), W_OK) != 0) return dir + "/: " + std::strerror(errno);
    return "";
}

double srgb_encode(double x)
{
    x = x < 0 ? 0 : x > 1 ? 1 : x;
    return x <= 0.0031308 ? 12.92 * x : 1.055 * std::pow(x, 1 / 2.4) - 0.055;
}

double srgb_decode(double y) { return y <= 0.04045 ? y / 12.92 : std::pow((y + 0.055) / 1.055, 2.4); }

} // namespace

extern "C" int ex_image_check_path(const char *path)
{
    if (format_of(path) != Format::unknown) return 0;
    return fail("write", path, "unknown image extension '" + extension_of(path) + "' (use .png or .exr)");
}

extern "C" int ex_image_write(const char *path, const float *rgb, int width, int height)
{
    Format f = format_of(path);
    if (f == Format::unknown) return ex_image_check_path(path);
    if (width <= 0 || height <= 0 || !rgb) return fail("write", path, "empty image");
    std::string dir_problem = directory_problem(path);
    if (!dir_problem.empty()) return fail("write", path, dir_problem);
    auto out = OIIO::ImageOutput::create(path);
    if (!out) return fail("write", path, OIIO::geterror());
    size_t n = (size_t)width * (size_t)height * 3;
    bool ok;
    if (f == Format::png) {
        std::vector<unsigned char> bytes(n);
        for (size_t i = 0; i < n; i++) bytes[i] = (unsigned char)std::lround(255.0 * srgb_encode(rgb[i]));
        OIIO::ImageSpec spec(width, height, 3, OIIO::TypeDesc::UINT8);
        spec.attribute("oiio:ColorSpace", "sRGB");
        ok = out->open(path, spec) && out->write_image(OIIO::TypeDesc::UINT8, bytes.data());
    } else {
        OIIO::ImageSpec spec(width, height, 3, OIIO::TypeDesc::HALF);
        spec.attribute("oiio:ColorSpace", "Linear");
        ok = out->open(path, spec) && out->write_image(OIIO::TypeDesc::FLOAT, rgb);
    }
    std::string err = ok ? "" : out->geterror();
    if (!out->close() && ok) { ok = false; err = out->geterror(); }
    return ok ? 0 : fail("write", path, err);
}

extern "C" int ex_image_read(const char *path, float **rgb, int *width, int *height)
{
    *rgb = nullptr;
    *width = *height = 0;
    auto in = OIIO::ImageInput::open(path);
    if (!in) {
        if (access(path, R_OK) != 0) return fail("read", path, std::strerror(errno));
        return fail("read", path, OIIO::geterror());
    }
    const OIIO::ImageSpec &spec = in->spec();
    int w = spec.width, h = spec.height, nch = spec.nchannels;
    if (w <= 0 || h <= 0 || nch <= 0) return fail("read", path, "empty image");
    std::vector<float> all((size_t)w * (size_t)h * (size_t)nch);
    if (!in->read_image(0, 0, 0, nch, OIIO::TypeDesc::FLOAT, all.data())) return fail("read", path, in->geterror());
    // integer formats (PNG, JPEG) hold sRGB-encoded values; float formats are linear
    bool encoded = !spec.format.is_floating_point();
    in->close();
    float *buf = (float *)std::malloc(sizeof(float) * 3 * (size_t)w * (size_t)h);
    if (!buf) return fail("read", path, "out of memory");
    for (size_t p = 0; p < (size_t)w * (size_t)h; p++)
        for (int c = 0; c < 3; c++) {
            double v = all[p * (size_t)nch + (size_t)(c < nch ? c : 0)];
            buf[3 * p + (size_t)c] = (float)(encoded ? srgb_decode(v) : v);
        }
    *rgb = buf;
    *width = w;
    *height = h;
    return 0;
}

extern "C" void ex_image_free(float *rgb) { std::free(rgb); }

extern "C" double ex_image_rmse(const float *a, const float *b, int width, int height)
{
    size_t n = (size_t)width * (size_t)height * 3;
    double s = 0;
    for (size_t i = 0; i < n; i++) s += ((double)a[i] - b[i]) * ((double)a[i] - b[i]);
    return n ? std::sqrt(s / (double)n) : 0.0;
}

extern "C" void ex_image_tonemap(float *rgb, int width, int height, double exposure_stops)
{
    const double knee = 0.6; // below: identity; above: exponential shoulder, C1 at the knee
    double gain = std::exp2(exposure_stops);
    size_t n = (size_t)width * (size_t)height * 3;
    for (size_t i = 0; i < n; i++) {
        double x = rgb[i] * gain;
        if (!(x > 0)) x = 0;
        if (x > knee) x = knee + (1 - knee) * (1 - std::exp(-(x - knee) / (1 - knee)));
        rgb[i] = (float)x;
    }
}

namespace {

int selftest_check(bool ok, const char *what, double value, double bound)
{
    std::printf("  image selftest: %-44s %.3g (bound %.3g): %s\n", what, value, bound, ok ? "ok" : "FAILED");
    return ok ? 0 : 1;
}

// Writes a gradient to `path`, reads it back and returns the largest error
// (in the encoded domain for PNG, relative for EXR); -1 on I/O failure.
double selftest_round_trip(const std::string &path, bool png)
{
    const int w = 37, h = 23; // odd sizes catch stride mistakes
    std::vector<float> img((size_t)w * h * 3);
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            float *p = &img[3 * ((size_t)y * w + x)];
            p[0] = (float)x / (w - 1);
            p[1] = (float)y / (h - 1);
            p[2] = png ? 0.5f : 0.001f + 40.0f * (float)(x * y) / (float)(w * h); // EXR: beyond [0, 1]
        }
    if (ex_image_write(path.c_str(), img.data(), w, h)) return -1;
    float *back = nullptr;
    int bw = 0, bh = 0;
    if (ex_image_read(path.c_str(), &back, &bw, &bh)) return -1;
    double worst = bw == w && bh == h ? 0 : 1e30;
    for (size_t i = 0; worst < 1e30 && i < img.size(); i++) {
        double e = png ? std::fabs(srgb_encode(back[i]) - srgb_encode(img[i]))
                       : std::fabs(back[i] - img[i]) / std::fabs(img[i]);
        if (e > worst) worst = e;
    }
    ex_image_free(back);
    return worst;
}

} // namespace

extern "C" int ex_image_selftest(const char *dir)
{
    int failures = 0;
    std::string base = std::string(dir) + "/ex_image_selftest_" + std::to_string((long)getpid());
    double e = selftest_round_trip(base + ".png", true);
    // 8-bit quantisation: half a step, plus float slack
    failures += selftest_check(e >= 0 && e <= 0.5 / 255 + 1e-6, "PNG round trip, max sRGB error", e, 0.5 / 255 + 1e-6);
    e = selftest_round_trip(base + ".exr", false);
    // half float: 11 significant bits, relative rounding error 2^-11
    failures += selftest_check(e >= 0 && e <= std::ldexp(1.0, -11), "EXR round trip, max relative error", e,
                               std::ldexp(1.0, -11));
    std::remove((base + ".png").c_str());
    std::remove((base + ".exr").c_str());
    float px[3] = {0, 0, 0};
    std::printf("  image selftest: the next two error lines are expected\n");
    std::fflush(stdout);
    int r = ex_image_write((base + ".bmpx").c_str(), px, 1, 1);
    failures += selftest_check(r == -1, "unknown extension is refused", r, -1);
    r = ex_image_write("/nonexistent-filigree-dir/x.png", px, 1, 1);
    failures += selftest_check(r == -1, "unwritable path is refused", r, -1);
    return failures;
}
