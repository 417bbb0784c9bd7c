#pragma once
/// \file
/// A small zlib stream encoder for the PNG writer: one deflate block with the fixed Huffman codes and greedy LZ77
/// matching (Deutsch, 1996, "DEFLATE Compressed Data Format Specification version 1.3", RFC 1951, sections 3.2.5
/// and 3.2.6; the zlib wrapper and its Adler-32 check: Deutsch & Gailly, 1996, RFC 1950). Matches are found
/// through a hash of the next three bytes and a chain of at most 16 earlier positions within the 32 KiB window.
/// Far from zlib's best on photographs, close to it on what sonar images and label images are made of: long runs
/// and rows that repeat.

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace sss::detail {

/// Bits written least significant first, as deflate packs them.
struct deflate_bits {
    std::vector<std::uint8_t>& out;
    std::uint32_t acc = 0;
    int n = 0;

    void put(std::uint32_t bits, int count) {
        acc |= bits << n;
        n += count;
        while (n >= 8) {
            out.push_back(static_cast<std::uint8_t>(acc & 0xffu));
            acc >>= 8;
            n -= 8;
        }
    }
    /// A Huffman code: its bits go most significant first.
    void code(std::uint32_t c, int len) {
        std::uint32_t r = 0;
        for (int i = 0; i < len; ++i) r |= ((c >> i) & 1u) << (len - 1 - i);
        put(r, len);
    }
    /// A literal/length symbol (0..287) in the fixed code (RFC 1951, 3.2.6).
    void symbol(std::uint32_t s) {
        if (s < 144) code(0x30 + s, 8);
        else if (s < 256) code(0x190 + (s - 144), 9);
        else if (s < 280) code(s - 256, 7);
        else code(0xC0 + (s - 280), 8);
    }
    void flush() {
        if (n > 0) out.push_back(static_cast<std::uint8_t>(acc & 0xffu));
        acc = 0;
        n = 0;
    }
};

/// The zlib stream (header 78 01, one fixed-code deflate block, Adler-32) of `raw`.
[[nodiscard]] inline std::vector<std::uint8_t> zlib_compress(std::span<const std::uint8_t> raw) {
    static constexpr std::uint16_t len_base[29] = {3,  4,  5,  6,  7,  8,  9,  10, 11,  13,  15,  17,  19,  23, 27,
                                                   31, 35, 43, 51, 59, 67, 83, 99, 115, 131, 163, 195, 227, 258};
    static constexpr std::uint8_t len_extra[29] = {0, 0, 0, 0, 0, 0, 0, 0, 1, 1, 1, 1, 2, 2, 2, 2, 3, 3, 3, 3, 4, 4, 4, 4, 5, 5, 5, 5, 0};
    static constexpr std::uint16_t dist_base[30] = {1,   2,   3,   4,   5,   7,    9,    13,   17,   25,   33,   49,   65,    97,    129,
                                                    193, 257, 385, 513, 769, 1025, 1537, 2049, 3073, 4097, 6145, 8193, 12289, 16385, 24577};
    static constexpr std::uint8_t dist_extra[30] = {0, 0, 0, 0, 1, 1, 2, 2, 3, 3, 4, 4, 5, 5, 6, 6, 7, 7, 8, 8, 9, 9, 10, 10, 11, 11, 12, 12, 13, 13};
    constexpr std::size_t window = 32768, max_len = 258, hash_bits = 15, max_chain = 16;
    constexpr std::int64_t none = -1;

    std::vector<std::uint8_t> z{0x78, 0x01};
    deflate_bits bits{z};
    bits.put(1, 1); // BFINAL
    bits.put(1, 2); // BTYPE 01: fixed Huffman codes
    const std::size_t n = raw.size();
    std::vector<std::int64_t> head(std::size_t(1) << hash_bits, none), prev(window, none);
    auto hash = [&](std::size_t i) {
        return ((std::size_t(raw[i]) << 10) ^ (std::size_t(raw[i + 1]) << 5) ^ std::size_t(raw[i + 2])) & ((std::size_t(1) << hash_bits) - 1);
    };
    auto insert = [&](std::size_t i) {
        if (i + 3 > n) return;
        const std::size_t h = hash(i);
        prev[i % window] = head[h];
        head[h] = static_cast<std::int64_t>(i);
    };
    for (std::size_t i = 0; i < n;) {
        std::size_t best = 0, dist = 0;
        if (i + 3 <= n) {
            const std::size_t limit = std::min(max_len, n - i);
            std::int64_t cand = head[hash(i)];
            for (std::size_t steps = 0; cand != none && steps < max_chain; ++steps) {
                const auto c = static_cast<std::size_t>(cand);
                if (i - c > window) break;
                std::size_t len = 0;
                while (len < limit && raw[c + len] == raw[i + len]) ++len;
                if (len > best) {
                    best = len;
                    dist = i - c;
                    if (len == limit) break;
                }
                const std::int64_t next = prev[c % window];
                if (next >= cand) break; // the slot was reused by a later position: the chain ends here
                cand = next;
            }
        }
        if (best >= 3) {
            std::size_t l = 28;
            while (len_base[l] > best) --l;
            bits.symbol(static_cast<std::uint32_t>(257 + l));
            bits.put(static_cast<std::uint32_t>(best - len_base[l]), len_extra[l]);
            std::size_t d = 29;
            while (dist_base[d] > dist) --d;
            bits.code(static_cast<std::uint32_t>(d), 5);
            bits.put(static_cast<std::uint32_t>(dist - dist_base[d]), dist_extra[d]);
            for (std::size_t k = 0; k < best; ++k) insert(i + k);
            i += best;
        } else {
            bits.symbol(raw[i]);
            insert(i);
            ++i;
        }
    }
    bits.symbol(256); // end of block
    bits.flush();
    std::uint32_t a = 1, b = 0; // Adler-32, big-endian after the data
    for (const std::uint8_t v : raw) {
        a = (a + v) % 65521u;
        b = (b + a) % 65521u;
    }
    const std::uint32_t adler = (b << 16) | a;
    for (int s = 24; s >= 0; s -= 8) z.push_back(static_cast<std::uint8_t>(adler >> s));
    return z;
}

} // namespace sss::detail
