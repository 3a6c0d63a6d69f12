// The image-loader target (imap::vision::load_grey8).
#include <cctype>
#include <cstring>
#include <new>
#include <opencv2/core.hpp>
#include <typeinfo>

#include "fuzz_vision.hpp"
#include "imap/vision/image_io.hpp"

namespace imap::fuzz {

namespace {

bool starts(const Bytes& b, const char* magic, size_t n) {
    return b.size() >= n && std::memcmp(b.data(), magic, n) == 0;
}

std::string format_of(const Bytes& b) {
    if (starts(b, "\x89PNG", 4)) return "png";
    if (starts(b, "\xff\xd8", 2)) return "jpeg";
    if (starts(b, "BM", 2)) return "bmp";
    if (b.size() >= 2 && b[0] == 'P' && b[1] >= '1' && b[1] <= '7') return "pnm";
    if (b.size() >= 2 && b[0] == 'P' && (b[1] == 'f' || b[1] == 'F')) return "pfm";
    if (starts(b, "II*", 3) || starts(b, "MM\0*", 4)) return "tiff";
    if (starts(b, "RIFF", 4)) return "webp";
    return "other";
}

uint32_t crc32(const uint8_t* p, size_t n) {
    static uint32_t table[256];
    static bool ready = false;
    if (!ready) {
        for (uint32_t i = 0; i < 256; ++i) {
            uint32_t c = i;
            for (int k = 0; k < 8; ++k) c = (c & 1) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
            table[i] = c;
        }
        ready = true;
    }
    uint32_t c = 0xFFFFFFFFu;
    for (size_t i = 0; i < n; ++i) c = table[(c ^ p[i]) & 0xFF] ^ (c >> 8);
    return c ^ 0xFFFFFFFFu;
}

uint32_t be32(const Bytes& b, size_t at) {
    return uint32_t{b[at]} << 24 | uint32_t{b[at + 1]} << 16 | uint32_t{b[at + 2]} << 8 | b[at + 3];
}
void put_be(Bytes& b, size_t at, uint32_t v, size_t width) {
    for (size_t k = 0; k < width && at + k < b.size(); ++k)
        b[at + k] = static_cast<uint8_t>(v >> (8 * (width - 1 - k)));
}
void put_le(Bytes& b, size_t at, uint32_t v, size_t width) {
    for (size_t k = 0; k < width && at + k < b.size(); ++k)
        b[at + k] = static_cast<uint8_t>(v >> (8 * k));
}

uint32_t interesting(Rng& rng) {
    static const uint32_t v[] = {
        0,     1,     2,      3,     4,          7,          8,          15,         16,
        24,    32,    255,    256,   1000,       4096,       32767,      32768,      65535,
        65536, 30000, 100000, 46341, 0x7fffffff, 0x80000000, 0xffffffff, 0xfffffffe, 17};
    return v[rng.index(sizeof v / sizeof v[0])];
}

struct Chunk {
    size_t pos;  // of the length field
    uint32_t len;
};

std::vector<Chunk> png_chunks(const Bytes& b) {
    std::vector<Chunk> out;
    size_t pos = 8;
    while (pos + 12 <= b.size()) {
        const uint32_t len = be32(b, pos);
        if (len > b.size() - pos - 12) break;
        out.push_back({pos, len});
        pos += 12 + len;
    }
    return out;
}

void fix_crc(Bytes& b, const Chunk& c) {
    put_be(b, c.pos + 8 + c.len, crc32(b.data() + c.pos + 4, 4 + c.len), 4);
}

void mutate_png(Rng& rng, Bytes& b, const std::vector<Bytes>& corpus) {
    std::vector<Chunk> ch = png_chunks(b);
    if (ch.empty()) return mutate_bytes(rng, b, corpus, 1 << 16, 3);
    const Chunk c = ch[rng.index(ch.size())];
    switch (rng.below(6)) {
        case 0: {  // IHDR fields: width, height, depth, colour type, interlace
            const Chunk& h = ch[0];
            if (h.len < 13) break;
            const size_t d = h.pos + 8;
            const uint64_t f = rng.below(5);
            if (f < 2)
                put_be(b, d + 4 * f, interesting(rng), 4);
            else
                b[d + 8 + (f - 2) * (f == 4 ? 2 : 1)] =
                    static_cast<uint8_t>(rng.chance(50) ? interesting(rng) : rng.below(17));
            fix_crc(b, h);
            break;
        }
        case 1: {  // the data of one chunk, then a good CRC
            Bytes data(b.begin() + static_cast<std::ptrdiff_t>(c.pos + 8),
                       b.begin() + static_cast<std::ptrdiff_t>(c.pos + 8 + c.len));
            mutate_bytes(rng, data, {}, 1 << 16, 2);
            Bytes out(b.begin(), b.begin() + static_cast<std::ptrdiff_t>(c.pos));
            const size_t at = out.size();
            out.resize(at + 8);
            put_be(out, at, static_cast<uint32_t>(data.size()), 4);
            std::memcpy(out.data() + at + 4, b.data() + c.pos + 4, 4);
            out.insert(out.end(), data.begin(), data.end());
            out.resize(out.size() + 4);
            out.insert(out.end(), b.begin() + static_cast<std::ptrdiff_t>(c.pos + 12 + c.len),
                       b.end());
            b.swap(out);
            fix_crc(b, {at, static_cast<uint32_t>(data.size())});
            break;
        }
        case 2: {  // duplicate or drop a chunk
            const Bytes blk(b.begin() + static_cast<std::ptrdiff_t>(c.pos),
                            b.begin() + static_cast<std::ptrdiff_t>(c.pos + 12 + c.len));
            if (rng.chance(50)) {
                const Chunk& d = ch[rng.index(ch.size())];
                b.insert(b.begin() + static_cast<std::ptrdiff_t>(d.pos), blk.begin(), blk.end());
            } else {
                b.erase(b.begin() + static_cast<std::ptrdiff_t>(c.pos),
                        b.begin() + static_cast<std::ptrdiff_t>(c.pos + 12 + c.len));
            }
            break;
        }
        case 3: {  // a chunk type (iCCP is dropped by the loader, PLTE/tRNS matter)
            static const char* types[] = {"iCCP", "PLTE", "tRNS", "IDAT", "IEND", "gAMA", "zzzz"};
            std::memcpy(b.data() + c.pos + 4, types[rng.index(7)], 4);
            fix_crc(b, c);
            break;
        }
        case 4:  // a chunk length
            put_be(b, c.pos, rng.chance(50) ? interesting(rng) : c.len + rng.below(9) - 4, 4);
            break;
        default:
            mutate_bytes(rng, b, corpus, 1 << 16, 3);
            break;
    }
}

void mutate_pnm(Rng& rng, Bytes& b, const std::vector<Bytes>& corpus) {
    // Header numbers (width, height, maxval, PAM fields) are the first tokens.
    std::vector<std::pair<size_t, size_t>> nums;
    for (size_t i = 2; i < b.size() && i < 80 && nums.size() < 4;) {
        if (std::isdigit(b[i])) {
            size_t e = i;
            while (e < b.size() && std::isdigit(b[e])) ++e;
            nums.emplace_back(i, e);
            i = e;
        } else {
            ++i;
        }
    }
    const uint64_t how = rng.below(4);
    if (how == 0 && !nums.empty()) {
        static const char* v[] = {"0",
                                  "1",
                                  "2",
                                  "255",
                                  "256",
                                  "65535",
                                  "65536",
                                  "-1",
                                  "4294967296",
                                  "99999",
                                  "46341",
                                  "30000",
                                  "100000000000000000000"};
        const auto [s, e] = nums[rng.index(nums.size())];
        const std::string n = v[rng.index(sizeof v / sizeof v[0])];
        b.erase(b.begin() + static_cast<std::ptrdiff_t>(s),
                b.begin() + static_cast<std::ptrdiff_t>(e));
        b.insert(b.begin() + static_cast<std::ptrdiff_t>(s), n.begin(), n.end());
    } else if (how == 1 && b.size() > 1) {
        b[1] = static_cast<uint8_t>('1' + rng.below(7));  // another PNM kind
    } else if (how == 2 && !nums.empty()) {               // a comment or junk inside the header
        static const char* ins[] = {"#c\n", " ", "\n", "x", "-", "#"};
        const std::string s = ins[rng.index(6)];
        const size_t at = nums[rng.index(nums.size())].first;
        b.insert(b.begin() + static_cast<std::ptrdiff_t>(at), s.begin(), s.end());
    } else {
        mutate_bytes(rng, b, corpus, 1 << 16, 3);
    }
}

void mutate_bmp(Rng& rng, Bytes& b, const std::vector<Bytes>& corpus) {
    static const std::pair<size_t, size_t> fields[] = {{2, 4},  {10, 4}, {14, 4}, {18, 4},
                                                       {22, 4}, {26, 2}, {28, 2}, {30, 4},
                                                       {34, 4}, {46, 4}, {50, 4}};
    if (rng.chance(60) && b.size() >= 54) {
        const auto [at, w] = fields[rng.index(sizeof fields / sizeof fields[0])];
        put_le(b, at, rng.chance(50) ? interesting(rng) : static_cast<uint32_t>(rng.below(40)), w);
    } else {
        mutate_bytes(rng, b, corpus, 1 << 16, 3);
    }
}

void mutate_jpeg(Rng& rng, Bytes& b, const std::vector<Bytes>& corpus) {
    std::vector<size_t> markers;  // positions of 0xFF xx with a length field
    for (size_t i = 2; i + 4 < b.size(); ++i)
        if (b[i] == 0xFF && b[i + 1] >= 0xC0 && b[i + 1] != 0xFF && b[i + 1] != 0xD8 &&
            b[i + 1] != 0xD9 && (b[i + 1] < 0xD0 || b[i + 1] > 0xD7))
            markers.push_back(i);
    if (rng.chance(60) && !markers.empty()) {
        const size_t m = markers[rng.index(markers.size())];
        if (b[m + 1] == 0xC0 || b[m + 1] == 0xC2) {  // SOF: precision, height, width, components
            static const size_t off[] = {4, 5, 7, 9};
            const size_t o = off[rng.index(4)];
            put_be(b, m + o, interesting(rng), o == 4 || o == 9 ? 1 : 2);
        } else {
            put_be(b, m + 2,
                   rng.chance(50) ? interesting(rng) : static_cast<uint32_t>(rng.below(40)), 2);
        }
    } else {
        mutate_bytes(rng, b, corpus, 1 << 16, 3);
    }
}

}  // namespace

Result check_image(const Bytes& file) {
    const std::string path = put_scratch_file("input.img", file);
    cv::Mat m;
    try {
        m = vision::load_grey8(path, "fuzz image");
    } catch (const vision::InputError& e) {
        const std::string w = e.what();
        if (w.find('\n') != std::string::npos)
            return {"InputError", "InputError message on several lines: " + w};
        return {signature("InputError", w), ""};
    } catch (const cv::Exception& e) {
        return {"cv::Exception", std::string("cv::Exception escaped load_grey8: ") + e.what()};
    } catch (const std::bad_alloc&) {
        return {"bad_alloc", "std::bad_alloc escaped load_grey8"};
    } catch (const std::exception& e) {
        return {"other exception",
                std::string("load_grey8 threw ") + typeid(e).name() + ": " + e.what()};
    }
    if (m.dims != 2 || m.type() != CV_8UC1 || m.rows <= 0 || m.cols <= 0 || !m.isContinuous() ||
        m.data == nullptr)
        return {"bad image", "load_grey8 returned type " + std::to_string(m.type()) + ", " +
                                 std::to_string(m.rows) + "x" + std::to_string(m.cols)};
    // Touch every pixel: the sanitizer build checks the buffer is that big.
    uint64_t sum = 0;
    for (size_t i = 0, n = m.total(); i < n; ++i) sum += m.data[i];
    (void)sum;
    return {"loaded " + format_of(file), ""};
}

void mutate_image(Rng& rng, Bytes& b, const std::vector<Bytes>& corpus) {
    const std::string f = format_of(b);
    if (rng.chance(20))
        mutate_bytes(rng, b, corpus, 1 << 16, 4);
    else if (f == "png")
        mutate_png(rng, b, corpus);
    else if (f == "pnm" || f == "pfm")
        mutate_pnm(rng, b, corpus);
    else if (f == "bmp")
        mutate_bmp(rng, b, corpus);
    else if (f == "jpeg")
        mutate_jpeg(rng, b, corpus);
    else
        mutate_bytes(rng, b, corpus, 1 << 16, 4);
}

}  // namespace imap::fuzz
