#include "vtkVolumeBricking.h"

#include <algorithm>
#include <cmath>

namespace mmv
{

int LargestBrickPoints(int points, int parts)
{
  if (points <= 1 || parts <= 1)
  {
    return std::max(points, 1);
  }
  const double delta = (points - 1.0) / parts;
  int largest = 0;
  for (int i = 0; i < parts; ++i)
  {
    const int first = static_cast<int>(i * delta);
    const int last = static_cast<int>((i + 1) * delta);
    largest = std::max(largest, last - first + 1);
  }
  return largest;
}

bool ChooseBrickPartitions(
  const int pointDims[3], int maxTextureSize, const int requested[3], int partitions[3])
{
  for (int a = 0; a < 3; ++a)
  {
    const int points = std::max(pointDims[a], 1);
    int parts = std::max(requested ? requested[a] : 1, 1);
    if (LargestBrickPoints(points, parts) > maxTextureSize)
    {
      if (maxTextureSize < 3)
      {
        return false;
      }
      // A brick spans at least (points - 1) / parts intervals, so fewer than
      // this cannot fit; rounding of the block ends may need one more.
      parts = static_cast<int>(std::ceil((points - 1.0) / (maxTextureSize - 1.0)));
      while (LargestBrickPoints(points, parts) > maxTextureSize && parts <= 65535)
      {
        ++parts;
      }
    }
    if (parts > 65535)
    {
      return false;
    }
    partitions[a] = parts;
  }
  return true;
}

bool LimitBrickBytes(
  const int pointDims[3], double bytesPerPoint, double maxBrickBytes, int partitions[3])
{
  auto brickBytes = [&]()
  {
    double bytes = bytesPerPoint;
    for (int a = 0; a < 3; ++a)
    {
      bytes *= LargestBrickPoints(std::max(pointDims[a], 1), partitions[a]);
    }
    return bytes;
  };
  while (brickBytes() > maxBrickBytes)
  {
    int longest = -1;
    for (int a = 0; a < 3; ++a)
    {
      const int points = LargestBrickPoints(std::max(pointDims[a], 1), partitions[a]);
      if (points > 2 && partitions[a] < 65535 &&
        (longest < 0 || points > LargestBrickPoints(pointDims[longest], partitions[longest])))
      {
        longest = a;
      }
    }
    if (longest < 0)
    {
      return false;
    }
    ++partitions[longest];
  }
  return true;
}

} // namespace mmv
