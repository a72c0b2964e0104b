#include "floorgrid/io/files/image_io.hpp"

#include <png.h>

#include <cctype>
#include <charconv>
#include <csetjmp>
#include <cstring>

#include "floorgrid/core/error.hpp"
#include "floorgrid/io/files/atomic_file.hpp"

namespace floorgrid::io {

namespace {

void check_size(const std::filesystem::path& path, long long width, long long height,
                const ImageLimits& limits) {
  if (width <= 0 || height <= 0) {
    throw InputError("image size " + std::to_string(width) + " x " + std::to_string(height) +
                         " is empty or negative",
                     path.string());
  }
  if (width > limits.max_side || height > limits.max_side ||
      static_cast<unsigned long long>(width) * static_cast<unsigned long long>(height) >
          limits.max_pixels) {
    throw InputError("image size " + std::to_string(width) + " x " + std::to_string(height) +
                         " is too large (the limit is " + std::to_string(limits.max_side) +
                         " pixels per side and " + std::to_string(limits.max_pixels) +
                         " in all, about 2.5 GB as a map): crop it or use a coarser resolution",
                     path.string());
  }
}

// ---- PGM ----

/// Reads the whitespace- and comment-separated header tokens of a PNM file.
class PnmHeader {
 public:
  PnmHeader(const std::string& bytes, const std::filesystem::path& path)
      : bytes_(bytes), path_(path) {}

  long long next_number(const char* what) {
    skip_space_and_comments();
    const char* begin = bytes_.data() + pos_;
    const char* end = bytes_.data() + bytes_.size();
    long long value = 0;
    const auto [ptr, ec] = std::from_chars(begin, end, value);
    if (ec != std::errc() || ptr == begin) {
      if (begin == end) {
        throw InputError(std::string("truncated file: it ends before the ") + what, path_.string());
      }
      throw InputError(std::string("bad ") + what + " in the PGM header", path_.string(), line_);
    }
    pos_ += static_cast<std::size_t>(ptr - begin);
    return value;
  }
  /// Position after the single whitespace byte that ends a P5 header.
  std::size_t data_start() {
    if (pos_ >= bytes_.size())
      throw InputError("file ends after the PGM header", path_.string());
    return pos_ + 1;
  }
  std::size_t position() const { return pos_; }
  void skip_space_and_comments() {
    while (pos_ < bytes_.size()) {
      const char c = bytes_[pos_];
      if (c == '#') {
        while (pos_ < bytes_.size() && bytes_[pos_] != '\n')
          ++pos_;
      } else if (std::isspace(static_cast<unsigned char>(c))) {
        if (c == '\n')
          ++line_;
        ++pos_;
      } else {
        break;
      }
    }
  }
  long line() const { return line_; }

 private:
  const std::string& bytes_;
  const std::filesystem::path& path_;
  std::size_t pos_ = 2;
  long line_ = 1;
};

GreyImage read_pgm(const std::string& bytes, const std::filesystem::path& path,
                   const ImageLimits& limits) {
  const bool ascii = bytes[1] == '2';
  PnmHeader header(bytes, path);
  const long long width = header.next_number("width");
  const long long height = header.next_number("height");
  const long long maxval = header.next_number("maxval");
  check_size(path, width, height, limits);
  if (maxval < 1 || maxval > 65535) {
    throw InputError("PGM maxval must be 1..65535 (got " + std::to_string(maxval) + ")",
                     path.string(), header.line(), "maxval");
  }
  GreyImage image;
  image.width = static_cast<int>(width);
  image.height = static_cast<int>(height);
  image.description =
      std::string("PGM ") + (ascii ? "P2" : "P5") + " maxval " + std::to_string(maxval);
  const std::size_t count = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  const std::size_t bytes_per_sample = maxval > 255 ? 2 : 1;
  if (!ascii) {
    const std::size_t start = header.data_start();
    const std::size_t needed = count * bytes_per_sample;
    // Checked before allocating: a header claiming a huge image in a small file is refused here.
    if (bytes.size() - start < needed) {
      throw InputError("truncated PGM: " + std::to_string(width) + " x " + std::to_string(height) +
                           " pixels need " + std::to_string(needed) +
                           " bytes of data, the file has " + std::to_string(bytes.size() - start),
                       path.string());
    }
    image.level.resize(count);
    image.max_level = static_cast<int>(maxval);
    const auto* data = reinterpret_cast<const unsigned char*>(bytes.data() + start);
    for (std::size_t i = 0; i < count; ++i) {
      const unsigned v = bytes_per_sample == 2 ? (data[2 * i] << 8u) | data[2 * i + 1] : data[i];
      if (v > maxval) {
        throw InputError(
            "pixel value " + std::to_string(v) + " exceeds maxval " + std::to_string(maxval),
            path.string(), 0, "pixel " + std::to_string(i));
      }
      image.level[i] = static_cast<std::uint16_t>(v);
    }
  } else {
    // An ASCII sample takes at least two bytes ("0 "): a short file cannot hold a huge image.
    if ((bytes.size() - header.position()) / 2 + 1 < count) {
      throw InputError("truncated PGM: too few samples for " + std::to_string(width) + " x " +
                           std::to_string(height) + " pixels",
                       path.string());
    }
    image.level.resize(count);
    image.max_level = static_cast<int>(maxval);
    for (std::size_t i = 0; i < count; ++i) {
      const long long v = header.next_number("pixel value");
      if (v < 0 || v > maxval) {
        throw InputError("pixel value " + std::to_string(v) + " outside 0..maxval", path.string(),
                         header.line());
      }
      image.level[i] = static_cast<std::uint16_t>(v);
    }
  }
  return image;
}

// ---- PNG (libpng's classic API: exact sample values, no gamma conversion) ----

struct PngReadState {
  const std::string* bytes;
  std::size_t pos = 8;
  std::string error;
};

void png_read_from_string(png_structp png, png_bytep out, png_size_t length) {
  auto* state = static_cast<PngReadState*>(png_get_io_ptr(png));
  if (state->bytes->size() - state->pos < length)
    png_error(png, "file ends early (truncated PNG)");
  std::memcpy(out, state->bytes->data() + state->pos, length);
  state->pos += length;
}

void png_on_error(png_structp png, png_const_charp message) {
  *static_cast<std::string*>(png_get_error_ptr(png)) = message;
  png_longjmp(png, 1);
}

void png_on_warning(png_structp, png_const_charp) {}

/// Owns libpng's read structures so that every exit, thrown or not, frees them.
struct PngReadGuard {
  png_structp png = nullptr;
  png_infop info = nullptr;
  ~PngReadGuard() { png_destroy_read_struct(&png, &info, nullptr); }
};

GreyImage read_png(const std::string& bytes, const std::filesystem::path& path,
                   const ImageLimits& limits) {
  PngReadState state{&bytes, 8, {}};
  PngReadGuard guard;
  guard.png =
      png_create_read_struct(PNG_LIBPNG_VER_STRING, &state.error, png_on_error, png_on_warning);
  if (guard.png == nullptr)
    throw std::bad_alloc();
  guard.info = png_create_info_struct(guard.png);
  if (guard.info == nullptr)
    throw std::bad_alloc();
  png_structp png = guard.png;
  png_infop info = guard.info;
  GreyImage image;
  std::vector<png_bytep> rows;
  std::vector<std::uint8_t> pixels;
  if (setjmp(png_jmpbuf(png)))
    throw InputError("malformed PNG: " + state.error, path.string());
  png_set_read_fn(png, &state, png_read_from_string);
  png_set_sig_bytes(png, 8);
  png_set_user_limits(png, static_cast<png_uint_32>(limits.max_side),
                      static_cast<png_uint_32>(limits.max_side));
  png_read_info(png, info);
  const png_uint_32 width = png_get_image_width(png, info);
  const png_uint_32 height = png_get_image_height(png, info);
  const int color_type = png_get_color_type(png, info);
  const int bit_depth = png_get_bit_depth(png, info);
  check_size(path, width, height, limits);

  png_set_expand(png);  // palette -> RGB, low-bit grey -> 8 bit, tRNS -> alpha
  png_set_scale_16(png);
  const int passes = png_set_interlace_handling(png);
  png_read_update_info(png, info);
  const int channels = png_get_channels(png, info);
  const std::size_t row_bytes = png_get_rowbytes(png, info);

  const bool color = channels >= 3;
  const bool has_alpha = channels == 2 || channels == 4;
  image.width = static_cast<int>(width);
  image.height = static_cast<int>(height);
  const char* kinds[] = {"grey", "grey+alpha", "RGB", "RGBA"};
  image.description = "PNG " + std::to_string(bit_depth) + "-bit " +
                      (color_type == PNG_COLOR_TYPE_PALETTE
                           ? std::string("palette (as ") + kinds[channels - 1] + ")"
                           : std::string(kinds[channels - 1]));
  const std::size_t count = static_cast<std::size_t>(width) * height;
  image.level.resize(count);
  image.max_level = color ? 3 * 255 : 255;  // RGB: the mean of the channels, kept exact as a sum
  if (has_alpha)
    image.alpha.resize(count);
  const auto keep_row = [&](png_uint_32 r, const std::uint8_t* row) {
    for (std::size_t x = 0; x < width; ++x) {
      const std::uint8_t* p = row + x * channels;
      const std::size_t i = static_cast<std::size_t>(r) * width + x;
      image.level[i] = static_cast<std::uint16_t>(color ? p[0] + p[1] + p[2] : p[0]);
      if (has_alpha)
        image.alpha[i] = p[channels - 1];
    }
  };
  if (passes == 1) {
    // Row by row: the decoded file never exists whole next to the image (an RGBA map of 4e8
    // pixels would take 1.6 GB more).
    pixels.resize(row_bytes);
    for (png_uint_32 r = 0; r < height; ++r) {
      png_read_row(png, pixels.data(), nullptr);
      keep_row(r, pixels.data());
    }
  } else {
    // Interlaced: the passes fill the whole image.
    pixels.resize(row_bytes * height);
    rows.resize(height);
    for (png_uint_32 r = 0; r < height; ++r)
      rows[r] = pixels.data() + r * row_bytes;
    png_read_image(png, rows.data());
    for (png_uint_32 r = 0; r < height; ++r)
      keep_row(r, rows[r]);
  }
  png_read_end(png, nullptr);
  return image;
}

// ---- writing ----

struct PngWriteState {
  std::string* out;
  std::string error;
};

void png_write_to_string(png_structp png, png_bytep data, png_size_t length) {
  auto* state = static_cast<PngWriteState*>(png_get_io_ptr(png));
  state->out->append(reinterpret_cast<const char*>(data), length);
}

void png_flush_nothing(png_structp) {}

/// Owns libpng's write structures.
struct PngWriteGuard {
  png_structp png = nullptr;
  png_infop info = nullptr;
  ~PngWriteGuard() { png_destroy_write_struct(&png, &info); }
};

// Whether `size` bytes are an image of this size with 1-4 channels.
bool buffer_fits(int width, int height, int channels, std::size_t size) {
  return width > 0 && height > 0 && channels >= 1 && channels <= 4 &&
         size == static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * channels;
}

}  // namespace

std::string encode_png(int width, int height, int channels,
                       const std::vector<std::uint8_t>& pixels) {
  if (!buffer_fits(width, height, channels, pixels.size()))
    throw std::invalid_argument("encode_png: the pixels do not match the image's size");
  std::string out;
  PngWriteState state{&out, {}};
  PngWriteGuard guard;
  guard.png =
      png_create_write_struct(PNG_LIBPNG_VER_STRING, &state.error, png_on_error, png_on_warning);
  if (guard.png == nullptr)
    throw std::bad_alloc();
  guard.info = png_create_info_struct(guard.png);
  if (guard.info == nullptr)
    throw std::bad_alloc();
  png_structp png = guard.png;
  png_infop info = guard.info;
  if (setjmp(png_jmpbuf(png)))
    throw std::runtime_error("PNG encoding failed: " + state.error);
  png_set_write_fn(png, &state, png_write_to_string, png_flush_nothing);
  const int color_type = channels == 1   ? PNG_COLOR_TYPE_GRAY
                         : channels == 2 ? PNG_COLOR_TYPE_GRAY_ALPHA
                         : channels == 3 ? PNG_COLOR_TYPE_RGB
                                         : PNG_COLOR_TYPE_RGB_ALPHA;
  png_set_IHDR(png, info, static_cast<png_uint_32>(width), static_cast<png_uint_32>(height), 8,
               color_type, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
               PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  const std::size_t row_bytes = static_cast<std::size_t>(width) * channels;
  for (int r = 0; r < height; ++r) {
    png_write_row(png, const_cast<png_bytep>(pixels.data() + r * row_bytes));
  }
  png_write_end(png, nullptr);
  return out;
}

namespace {

void check_buffer(const std::filesystem::path& path, int width, int height, int channels,
                  std::size_t size) {
  if (!buffer_fits(width, height, channels, size))
    throw std::invalid_argument("image buffer does not match its size for " + path.string());
}

}  // namespace

GreyImage read_grey_image(const std::filesystem::path& path, const ImageLimits& limits) {
  const std::string bytes = read_whole_file(path);
  static const unsigned char kPngSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  if (bytes.size() >= 8 && std::memcmp(bytes.data(), kPngSignature, 8) == 0) {
    return read_png(bytes, path, limits);
  }
  if (bytes.size() >= 2 && bytes[0] == 'P' && (bytes[1] == '5' || bytes[1] == '2')) {
    return read_pgm(bytes, path, limits);
  }
  if (bytes.empty())
    throw InputError("empty file: expected a PGM or PNG image", path.string());
  throw InputError("not a PGM (P2/P5) or PNG image (unknown magic bytes)", path.string());
}

void write_pgm(const std::filesystem::path& path, int width, int height,
               const std::vector<std::uint8_t>& pixels) {
  check_buffer(path, width, height, 1, pixels.size());
  std::string bytes = "P5\n" + std::to_string(width) + " " + std::to_string(height) + "\n255\n";
  bytes.append(reinterpret_cast<const char*>(pixels.data()), pixels.size());
  write_file_atomically(path, bytes);
}

void write_png(const std::filesystem::path& path, int width, int height,
               const std::vector<std::uint8_t>& grey, const std::vector<std::uint8_t>& alpha) {
  check_buffer(path, width, height, 1, grey.size());
  if (alpha.empty()) {
    write_file_atomically(path, encode_png(width, height, 1, grey));
    return;
  }
  check_buffer(path, width, height, 1, alpha.size());
  std::vector<std::uint8_t> interleaved(grey.size() * 2);
  for (std::size_t i = 0; i < grey.size(); ++i) {
    interleaved[2 * i] = grey[i];
    interleaved[2 * i + 1] = alpha[i];
  }
  write_file_atomically(path, encode_png(width, height, 2, interleaved));
}

void write_png_rgb(const std::filesystem::path& path, int width, int height,
                   const std::vector<std::uint8_t>& rgb) {
  check_buffer(path, width, height, 3, rgb.size());
  write_file_atomically(path, encode_png(width, height, 3, rgb));
}

void write_png_rgba(const std::filesystem::path& path, int width, int height,
                    const std::vector<std::uint8_t>& rgba) {
  check_buffer(path, width, height, 4, rgba.size());
  write_file_atomically(path, encode_png(width, height, 4, rgba));
}

}  // namespace floorgrid::io
