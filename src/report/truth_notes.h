#pragma once
// What a report says about its truth: how many rays it traced per pixel towards each light (one
// exact ray towards a light without a size), and the note a soft technique ranked against such a
// hard truth gets.
#include <cstdint>
#include <string>
#include <vector>

namespace penumbra {

struct ReportData;

// The truth's rays per pixel towards each light: `samples` towards a light with a size, one
// exact ray towards one without. `sized` holds one flag per light.
std::vector<uint32_t> truthRays(uint32_t samples, const std::vector<bool>& sized);

// The same in words: "256 rays per pixel and light", "1 exact ray per pixel and light (no light
// has a size: a hard truth)", "256 rays per pixel towards the 1 light with a size, 1 exact ray
// towards the 2 without"; "no shadow-casting light" when `sized` is empty.
std::string truthRaysText(uint32_t samples, const std::vector<bool>& sized);

// Per light of the report: data.lightSized, or every light sized where it is empty.
std::vector<bool> lightsSized(const ReportData& data);

// When a light has no size (its truth is hard) and a row that ran models the light's size: the
// note that names both (its penumbra counts as error there). Empty otherwise.
std::string hardTruthNote(const ReportData& data);

} // namespace penumbra
