// Format dispatch, file extensions and the write-to-temporary-then-rename step every writer uses.
#include "obscura/image_io.h"

#include "obscura/error.h"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cerrno>
#include <cstdio>
#include <filesystem>
#include <system_error>

namespace obscura {

namespace fs = std::filesystem;

std::string fileExtension(const std::string& path) {
    std::string ext = fs::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return ext;
}

Image readImage(const std::string& path) {
    const std::string ext = fileExtension(path);
    if (ext == ".exr") return readExr(path);
    if (ext == ".png") return readPng(path);
    if (ext == ".hdr") return readHdr(path);
    if (ext.empty()) fail(path, "no file extension to tell the image format (expected .exr, .png or .hdr)");
    fail(path, "unknown image format '" + ext + "' (expected .exr, .png or .hdr)");
}

Image readEnvironmentImage(const std::string& path) {
    return fileExtension(path) == ".exr" ? readExrDisplayWindow(path) : readImage(path);
}

namespace {

// `text` cut to at most `bytes`, never inside a UTF-8 character: a name cut mid-character is no valid UTF-8,
// which some file systems refuse.
std::string cutUtf8(const std::string& text, std::size_t bytes) {
    if (text.size() <= bytes) return text;
    std::size_t end = bytes;
    while (end > 0 && (static_cast<unsigned char>(text[end]) & 0xC0) == 0x80) --end;  // text[end] continues one
    return text.substr(0, end);
}

std::string temporaryPathFor(const std::string& path) {
    // The pid keeps concurrent processes apart, the counter concurrent threads of this one.
    static std::atomic<unsigned long> counter{0};
    const std::string suffix = ".tmp-" + std::to_string(getpid()) + "-" + std::to_string(counter++);
    // Beside the output, in a name a file system takes: a valid output name of 230 bytes and more once became a
    // temporary past NAME_MAX (255 on Linux), and the write failed with "File name too long".
    const fs::path target(path);
    const std::string name = target.filename().string();
    constexpr std::size_t kMaxName = 255;
    if (name.size() + suffix.size() <= kMaxName) return path + suffix;
    return (target.parent_path() / (cutUtf8(name, kMaxName - suffix.size()) + suffix)).string();
}

// Creating the temporary up front (exclusively, so a stale or foreign file is never reused) turns a
// missing or read-only directory into one clear message before any format library gets involved.
void createEmptyFile(const std::string& path, const std::string& tempPath) {
    std::FILE* file = std::fopen(tempPath.c_str(), "wbx");
    if (!file) {
        const int err = errno;
        const fs::path dir = fs::path(path).parent_path();
        std::error_code ec;
        if (!dir.empty() && !fs::is_directory(dir, ec))
            fail(path, "cannot write: directory '" + dir.string() + "' does not exist");
        fail(path, "cannot write: " + std::generic_category().message(err));
    }
    std::fclose(file);
}

} // namespace

void checkWritable(const std::string& path) {
    const std::string temp = temporaryPathFor(path);
    createEmptyFile(path, temp);
    std::error_code ignored;
    fs::remove(temp, ignored);
}

void writeFilesTogether(const std::vector<FileWriter>& files) {
    std::vector<std::string> temporaries;
    for (const FileWriter& f : files) temporaries.push_back(temporaryPathFor(f.path));
    const auto removeTemporaries = [&] {
        std::error_code ec;
        for (const std::string& t : temporaries) fs::remove(t, ec);
    };
    for (std::size_t i = 0; i < files.size(); ++i) {
        try {
            files[i].write(temporaries[i]);
        } catch (const Error& e) {
            removeTemporaries();
            std::string message = e.what();
            for (std::size_t at; (at = message.find(temporaries[i])) != std::string::npos;)
                message.replace(at, temporaries[i].size(), files[i].path);
            throw Error(message);
        } catch (...) {
            removeTemporaries();
            throw;
        }
    }
    for (std::size_t i = 0; i < files.size(); ++i) {
        std::error_code ec;
        fs::rename(temporaries[i], files[i].path, ec);
        if (ec) {
            removeTemporaries();
            fail(files[i].path, "cannot write: " + ec.message());
        }
    }
}

void writeAtomically(const std::string& path, const std::function<void(const std::string& tempPath)>& write) {
    const std::string tempPath = temporaryPathFor(path);
    createEmptyFile(path, tempPath);
    try {
        write(tempPath);
        std::error_code ec;
        fs::rename(tempPath, path, ec);
        if (ec) fail(path, "cannot write: " + ec.message());
    } catch (...) {
        std::error_code ignored; // the original exception is the one worth reporting
        fs::remove(tempPath, ignored);
        throw;
    }
}

} // namespace obscura
