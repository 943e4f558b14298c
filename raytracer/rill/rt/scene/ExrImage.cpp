// OpenEXR files through the OpenEXR library (ExrImage.h). The file is encoded into memory and
// then written with checked I/O: OpenEXR's OutputFile writes the line offset table in its
// destructor, where it swallows errors, and a file stream reports a full disk only when it is
// flushed, so that writing straight to the file could leave a truncated image behind.
#include "rill/rt/scene/ExrImage.h"

#include <IexBaseExc.h>
#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfIO.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <set>

#include "rill/rt/scene/ImageLimits.h"
#include "rill/rt/scene/InputFile.h"
#include "rill/rt/scene/OutputFile.h"
#include "rill/rt/scene/Scene.h"

namespace rt {

namespace {

// An OpenEXR output stream into a string.
class MemoryOStream : public Imf::OStream {
 public:
  MemoryOStream() : Imf::OStream("memory") {}
  void write(const char c[], int n) override {
    const size_t count = static_cast<size_t>(n);
    if (pos_ + count > bytes_.size()) bytes_.resize(pos_ + count);
    std::memcpy(bytes_.data() + pos_, c, count);
    pos_ += count;
  }
  uint64_t tellp() override { return pos_; }
  void seekp(uint64_t pos) override { pos_ = static_cast<size_t>(pos); }
  const std::string& bytes() const { return bytes_; }

 private:
  std::string bytes_;
  size_t pos_ = 0;
};

// An OpenEXR input stream over a string.
class MemoryIStream : public Imf::IStream {
 public:
  MemoryIStream(const std::string& bytes, const std::string& path)
      : Imf::IStream(path.c_str()), bytes_(bytes) {}
  bool read(char c[], int n) override {
    const size_t count = static_cast<size_t>(n);
    if (pos_ > bytes_.size() || count > bytes_.size() - pos_)
      throw Iex::InputExc("unexpected end of file");
    std::memcpy(c, bytes_.data() + pos_, count);
    pos_ += count;
    return pos_ < bytes_.size();
  }
  uint64_t tellg() override { return pos_; }
  void seekg(uint64_t pos) override { pos_ = static_cast<size_t>(pos); }

 private:
  const std::string& bytes_;
  size_t pos_ = 0;
};

// The EXR file's bytes for these channels.
std::string encode(int width, int height, const std::vector<ExrChannel>& channels) {
  Imf::Header header(width, height);
  header.compression() = Imf::ZIP_COMPRESSION;
  header.lineOrder() = Imf::INCREASING_Y;
  Imf::FrameBuffer fb;
  const size_t row = static_cast<size_t>(width);
  for (const ExrChannel& c : channels) {
    const bool is_float = c.type == ExrType::Float;
    const Imf::PixelType type = is_float ? Imf::FLOAT : Imf::UINT;
    // OpenEXR's Slice takes a non-const pointer; writing only reads it.
    char* base = const_cast<char*>(is_float ? reinterpret_cast<const char*>(c.floats)
                                            : reinterpret_cast<const char*>(c.uints));
    header.channels().insert(c.name, Imf::Channel(type));
    const size_t step = 4 * static_cast<size_t>(c.step);
    fb.insert(c.name, Imf::Slice(type, base, step, step * row));
  }
  MemoryOStream out;
  {
    Imf::OutputFile file(out, header);
    file.setFrameBuffer(fb);
    file.writePixels(height);
  }  // the destructor writes the line offset table
  return out.bytes();
}

}  // namespace

void write_exr(const std::string& path, int width, int height,
               const std::vector<ExrChannel>& channels) {
  if (width < 1 || height < 1)
    throw SceneError("cannot write " + path + ": a " + std::to_string(width) + "x" +
                     std::to_string(height) + " image");
  std::set<std::string> names;
  for (const ExrChannel& c : channels) {
    if ((c.type == ExrType::Float ? static_cast<const void*>(c.floats)
                                  : static_cast<const void*>(c.uints)) == nullptr)
      throw SceneError("cannot write " + path + ": channel '" + c.name + "' has no data");
    if (c.step < 1)
      throw SceneError("cannot write " + path + ": channel '" + c.name + "' has step " +
                       std::to_string(c.step));
    if (!names.insert(c.name).second)
      throw SceneError("cannot write " + path + ": two channels named '" + c.name + "'");
  }
  std::string bytes;
  try {
    bytes = encode(width, height, channels);
  } catch (const std::exception& e) {
    throw SceneError("cannot write " + path + ": " + e.what());
  }
  write_output_file(path, bytes);
}

const ExrImage::Channel* ExrImage::find(const std::string& name) const {
  for (const Channel& c : channels)
    if (c.name == name) return &c;
  return nullptr;
}

ExrImage read_exr(const std::string& path) {
  const std::string bytes = read_input_file(path, "an OpenEXR file");
  try {
    MemoryIStream in(bytes, path);
    Imf::InputFile file(in);
    const Imath::Box2i dw = file.header().dataWindow();
    ExrImage image;
    // A header's size and channels are checked before allocating (ImageLimits.h): a data
    // window of 2^31 x 2^31 pixels, or thousands of channels, in a small file is an error, not
    // an allocation of exabytes.
    const Imf::ChannelList& list = file.header().channels();
    int64_t channels = 0;
    for (auto it = list.begin(); it != list.end(); ++it) ++channels;
    check_declared_image(path, "EXR", static_cast<int64_t>(dw.max.x) - dw.min.x + 1,
                         static_cast<int64_t>(dw.max.y) - dw.min.y + 1, channels);
    image.width = dw.max.x - dw.min.x + 1;
    image.height = dw.max.y - dw.min.y + 1;
    const size_t n = static_cast<size_t>(image.width) * static_cast<size_t>(image.height);
    const size_t row = static_cast<size_t>(image.width);
    for (auto it = list.begin(); it != list.end(); ++it) {
      if (it.channel().xSampling != 1 || it.channel().ySampling != 1)
        throw SceneError(path + ": channel '" + it.name() + "' is subsampled (not supported)");
      image.channels.push_back(
          {it.name(), it.channel().type == Imf::UINT ? ExrType::Uint : ExrType::Float, {}, {}});
    }
    Imf::FrameBuffer fb;
    for (ExrImage::Channel& c : image.channels) {
      void* data = nullptr;
      if (c.type == ExrType::Uint) {
        c.uints.resize(n);
        data = c.uints.data();
      } else {
        c.floats.resize(n);
        data = c.floats.data();
      }
      fb.insert(c.name, Imf::Slice::Make(c.type == ExrType::Uint ? Imf::UINT : Imf::FLOAT, data, dw,
                                         4, 4 * row));
    }
    file.setFrameBuffer(fb);
    file.readPixels(dw.min.y, dw.max.y);
    return image;
  } catch (const SceneError&) {
    throw;
  } catch (const std::exception& e) {
    throw SceneError(path + ": not a readable OpenEXR file (" + std::string(e.what()) + ")");
  }
}

}  // namespace rt
