#include "key_decoder.h"

#include <array>

#include <linux/input-event-codes.h>

namespace hubrt::hal::rfid {
namespace {

struct KeyChars {
  char plain = 0;
  char shifted = 0;
};

// US layout, the keys a badge can hold (linux/input-event-codes.h numbers them).
constexpr std::array<KeyChars, KEY_KPDOT + 1> make_keymap() {
  std::array<KeyChars, KEY_KPDOT + 1> map{};
  constexpr const char* kDigits = "1234567890";
  constexpr const char* kDigitsShifted = "!@#$%^&*()";
  for (int i = 0; i < 10; ++i) map[KEY_1 + i] = {kDigits[i], kDigitsShifted[i]};
  map[KEY_MINUS] = {'-', '_'};
  map[KEY_EQUAL] = {'=', '+'};
  constexpr const char* kRows[] = {"qwertyuiop", "asdfghjkl", "zxcvbnm"};
  constexpr int kRowStart[] = {KEY_Q, KEY_A, KEY_Z};
  for (int row = 0; row < 3; ++row) {
    for (int i = 0; kRows[row][i] != '\0'; ++i) {
      const char c = kRows[row][i];
      map[kRowStart[row] + i] = {c, static_cast<char>(c - 'a' + 'A')};
    }
  }
  map[KEY_SPACE] = {' ', ' '};
  map[KEY_DOT] = {'.', '>'};
  map[KEY_COMMA] = {',', '<'};
  map[KEY_SLASH] = {'/', '?'};
  map[KEY_SEMICOLON] = {';', ':'};
  // The keypad: some readers type their digits there.
  constexpr std::array<int, 10> kPad = {KEY_KP0, KEY_KP1, KEY_KP2, KEY_KP3, KEY_KP4,
                                        KEY_KP5, KEY_KP6, KEY_KP7, KEY_KP8, KEY_KP9};
  for (int i = 0; i < 10; ++i) map[kPad[i]] = {static_cast<char>('0' + i), static_cast<char>('0' + i)};
  map[KEY_KPMINUS] = {'-', '-'};
  map[KEY_KPPLUS] = {'+', '+'};
  map[KEY_KPDOT] = {'.', '.'};
  return map;
}

constexpr auto kKeymap = make_keymap();

bool is_shift(std::uint16_t code) noexcept {
  return code == KEY_LEFTSHIFT || code == KEY_RIGHTSHIFT;
}

// Keys a reader may press around its text that mean nothing for the badge.
bool is_other_modifier(std::uint16_t code) noexcept {
  switch (code) {
    case KEY_LEFTCTRL:
    case KEY_RIGHTCTRL:
    case KEY_LEFTALT:
    case KEY_RIGHTALT:
    case KEY_LEFTMETA:
    case KEY_RIGHTMETA:
    case KEY_CAPSLOCK:
    case KEY_NUMLOCK:
      return true;
    default:
      return false;
  }
}

}  // namespace

bool KeyDecoder::feed(std::uint16_t type, std::uint16_t code, std::int32_t value, BadgeRead& out,
                      Time now) noexcept {
  if (type != EV_KEY) return false;  // EV_SYN, EV_MSC (scan codes), EV_LED: nothing for the badge
  if (is_shift(code)) {
    if (value == 1) ++shift_;
    if (value == 0 && shift_ > 0) --shift_;
    return false;
  }
  if (value != 1) return false;  // release (0) or auto-repeat (2)
  if (code == KEY_ENTER || code == KEY_KPENTER) return line_.end(out, now);
  if (is_other_modifier(code)) return false;
  if (code < kKeymap.size() && kKeymap[code].plain != 0) {
    line_.add(shift_ > 0 ? kKeymap[code].shifted : kKeymap[code].plain, now);
    return false;
  }
  line_.add_garbage("a key that is no badge character", now);
  return false;
}

void KeyDecoder::events_lost(Time now) noexcept {
  if (line_.in_progress()) line_.add_garbage("input events lost (SYN_DROPPED)", now);
  shift_ = 0;
}

}  // namespace hubrt::hal::rfid
